#pragma once
// OBJ's normal rule for faces that give no vertex normals (docs/scene.md "Model files"): such a face is
// flat unless a nonzero smoothing group ("s 1", "s 2", ...) is active, in which case its corners take the
// group's smooth normal at that vertex. assimp 5.2 ignores "s" statements (its OBJ parser skips the
// line), so bounce reads them itself: it rewrites the file's text, giving every such face explicit
// normals, and hands assimp the rewritten text.
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

namespace bounce {

struct ObjNormalsRewrite {
    std::string text;        // the OBJ with normals for every face
    size_t flatFaces = 0;    // faces given their own face normal (no smoothing group)
    size_t smoothFaces = 0;  // faces given smoothing-group vertex normals
};

// Adds "vn" lines at the end of `obj` and references them from every face ("f") that has no normals:
// a face outside any smoothing group ("s 0", "s off", or none yet) gets its polygon normal (Newell's
// method, following the face's counter-clockwise winding); a face in smoothing group g gets, at each
// corner, the normalised sum of the unit normals of group g's faces using that vertex ("v" index),
// each weighted by the face's angle at the vertex. Faces that give normals, "l" and "p" statements
// and every other line are kept as written. Returns nullopt when no face lacks normals, or when a
// face cannot be read (then assimp reads the file unchanged and reports it).
std::optional<ObjNormalsRewrite> addMissingObjNormals(std::string_view obj);

}  // namespace bounce
