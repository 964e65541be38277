// The shadow techniques, one line each, in the order help texts and panels list them.
// C++ (techniques.cpp) and the build's GLSL dispatch (cmake/ShadowTechniques.cmake)
// both read this list; a technique <name> lives in passes/shadows/techniques/<name>/.
AVSM_SHADOW_TECHNIQUE(avsm)
AVSM_SHADOW_TECHNIQUE(uncompressed)
AVSM_SHADOW_TECHNIQUE(osm)
AVSM_SHADOW_TECHNIQUE(fom)
AVSM_SHADOW_TECHNIQUE(dsm)
AVSM_SHADOW_TECHNIQUE(constant)
