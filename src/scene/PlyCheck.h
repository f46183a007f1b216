#pragma once
// A structural check of PLY files before assimp reads them (docs/scene.md "Model files"). assimp 5.2's
// PLY reader does not survive some malformed files: a header without "end_header" makes it loop
// forever ("ply\nformat ascii 1.0\n") or read past the end of its buffer (a truncated binary header),
// which no error handling after the call can catch. bounce therefore reads the header itself and,
// for the binary encodings, walks the body to see that every element the header declares fits in the
// file; a file that passes is what assimp's reader handles.
#include "core/Error.h"

#include <string>
#include <string_view>

namespace bounce {

// `bytes` is the whole file; `where` starts the message ("scene.json:4: object 'x': model 'a.ply'").
// Errors name the header line or the element that is wrong.
Expected<void> checkPlyFile(std::string_view bytes, const std::string& where);

}  // namespace bounce
