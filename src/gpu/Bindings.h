// Binding points shared by C++ and GLSL. ShaderLibrary prepends this file to every shader, and C++
// includes it, so an index is written exactly once. Plain #defines only (valid in both languages).
#ifndef BOUNCE_BINDINGS_H
#define BOUNCE_BINDINGS_H

// Uniform buffers
#define BINDING_UBO_FRAME 0    // FrameUniforms: camera matrices, viewport, time
#define BINDING_UBO_VIEW 1     // ViewUniforms: the view a SceneDrawer pass renders from
#define BINDING_UBO_LIGHT 2    // LightUniforms: one light for a shading or shadow pass
#define BINDING_UBO_PASS 3     // per-pass parameters owned by a technique
#define BINDING_UBO_VOXELS 4   // ScreenVoxelsGpu: the screen-space voxel grid (techniques/screen_voxels)
#define BINDING_UBO_VPL_WINDOW 5  // a window of a VPL cache read as a uniform block (techniques/nichols/vpl_window.glsl)
#define BINDING_UBO_VOXELS_OUTER 6  // ScreenVoxelsGpu of a second grid beyond the camera's frustum (area-light, march.glsl SV_OUTER_GRID)

// Shader storage buffers
#define BINDING_SSBO_OBJECTS 0    // ObjectGpu[]: worldFromObject, normal matrix, material index
#define BINDING_SSBO_MATERIALS 1  // MaterialGpu[]
#define BINDING_SSBO_VOXEL_RAYS 2  // ray counters of the RSM-family gathers' optional VPL visibility (screen_voxels)
#define BINDING_SSBO_TECH0 4      // technique-owned buffers start here
#define BINDING_SSBO_TECH1 5
#define BINDING_SSBO_TECH2 6
#define BINDING_SSBO_TECH3 7
// Hemicube radiosity (techniques/radiosity): its eight record arrays (GL 4.5 drivers bounce targets
// have at least 16 storage-buffer bindings; llvmpipe and NVIDIA expose 32 and 96).
#define BINDING_SSBO_RAD_QUADS 8
#define BINDING_SSBO_RAD_ELEMENTS 9
#define BINDING_SSBO_RAD_TRIANGLES 10
#define BINDING_SSBO_RAD_BODIES 11
#define BINDING_SSBO_RAD_BODIES_OLD 12
#define BINDING_SSBO_RAD_SHOOTERS 13
#define BINDING_SSBO_RAD_HEMICUBES 14
#define BINDING_SSBO_RAD_STATS 15

// Texture units
#define BINDING_TEX_BASECOLOR 0   // sampler2DArray of all base-colour textures
#define BINDING_TEX_GBUF_POSITION 1
#define BINDING_TEX_GBUF_NORMAL 2
#define BINDING_TEX_GBUF_ALBEDO 3
#define BINDING_TEX_GBUF_EMISSION 4
#define BINDING_TEX_SHADOW 5      // the current light's shadow map (2D)
#define BINDING_TEX_SHADOW_CUBE 6 // the current light's cube shadow map (point, area)
#define BINDING_TEX_AREA_LIGHT 7  // the current area light's emission texture (mipmapped; 1x1 white if none)
#define BINDING_TEX_INPUT0 8      // generic inputs of full-screen passes
#define BINDING_TEX_INPUT1 9
#define BINDING_TEX_INPUT2 10
#define BINDING_TEX_INPUT3 11
#define BINDING_TEX_TECH0 12      // technique-owned textures start here
#define BINDING_TEX_TECH1 13
#define BINDING_TEX_TECH2 14
#define BINDING_TEX_TECH3 15
// Voxel cone tracing (techniques/vct) samples up to 13 volumes at once and its voxelizer up to four
// lights' shadow maps; GL 4.5 guarantees 32 texture units per stage (16 per fragment stage in the
// minimum, every driver bounce targets has 32).
#define BINDING_TEX_VCT_ALPHA 16     // isotropic RGBA8 volume: colour, and opacity for every format
#define BINDING_TEX_VCT_VOLUME0 17   // aniso faces 17..22, SH-F32 coefficients 17..28, SH-U8 17..19
#define BINDING_TEX_VCT_SHADOW2D0 24 // voxelizer: light k's 2D shadow map at 24 + k (k < 4)
#define BINDING_TEX_VCT_SHADOWCUBE0 28 // voxelizer: light k's cube distance map at 28 + k
// Screen-space binary voxels (techniques/screen_voxels): usampler2DArray, one layer per 128 bits. Unit 16
// is also vct's; the two are never bound in one pass.
#define BINDING_TEX_VOXELS 16
#define BINDING_TEX_VOXELS_OUTER 17  // the second grid (march.glsl SV_OUTER_GRID); vct's unit too, never bound in one pass with it
// Min-max pyramids (techniques/nichols/pyramid_reduce.comp) read level k-1 of their five chains here:
// units past every pass's own (GL 4.5 guarantees 80 combined units; a stage's count stays <= 16).
#define BINDING_TEX_PYRAMID0 32
#define BINDING_TEX_PYRAMID1 33
#define BINDING_TEX_PYRAMID2 34
#define BINDING_TEX_PYRAMID3 35
#define BINDING_TEX_PYRAMID4 36

// Image units
#define BINDING_IMG0 0
#define BINDING_IMG1 1
#define BINDING_IMG2 2
#define BINDING_IMG3 3
#define BINDING_IMG4 4  // min-max pyramids (techniques/nichols) write five images (and read level k-1 by samplers)
#define BINDING_IMG5 5
#define BINDING_IMG6 6
#define BINDING_IMG7 7  // the highest unit: GL 4.5 and NVIDIA's driver have 8 image units (issue 29 finding #1)

// Vertex attribute locations
#define ATTR_POSITION 0
#define ATTR_NORMAL 1
#define ATTR_UV 2
#define ATTR_OBJECT_INDEX 3  // per-instance; the draw's baseInstance selects the object
#define ATTR_TANGENT 4  // vec4 tangent (xyz) and bitangent sign (w); w = 0: the mesh has none

#endif
