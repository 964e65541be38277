// Push constants of a technique's map build from the capture lists (avsm_resolve, osm_build, fom_build, dsm_build).
#ifndef AVSM_SHARED_PASSES_MAP_BUILD_H
#define AVSM_SHARED_PASSES_MAP_BUILD_H
#include "shared/gpu_struct.h"
GPU_NAMESPACE_BEGIN

#define GPU_MAP_BUILD_PUSH(F, A)                                                                 \
  F(uint, resolution)                                                                            \
  F(uint, count)        /* avsm: N nodes; osm: K planes; fom: K terms; dsm: the dispatch */      \
  F(float, near_depth)  /* the light's caster depth range the map covers */                      \
  F(float, far_depth)                                                                            \
  F(float, error)       /* error threshold (dsm) */
GPU_PUSH_CONSTANTS(MapBuildPush, GPU_MAP_BUILD_PUSH)

GPU_NAMESPACE_END
#endif
