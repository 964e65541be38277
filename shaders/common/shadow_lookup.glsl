// Transmittance from a light to a world point: the one place every camera pass
// asks about shadows (GpuShadow: shared/shadow.h).
//
// Four storage buffers (read only): the GpuShadow records, the map atlas and
// (uncompressed reference) the capture list heads and nodes. Each record finds its data
// at its own offsets in them, so any number of lights and maps share four bindings.
// Before including, say where they are, either
//   #define AVSM_SHADOW_BINDING b          // at bindings b, b + 1, b + 2, b + 3
// or each one (the host's own numbers; they need not be consecutive):
//   #define AVSM_SHADOW_PARAMETERS_BINDING 7
//   #define AVSM_SHADOW_ATLAS_BINDING 2
//   #define AVSM_SHADOW_LIST_HEADS_BINDING 3
//   #define AVSM_SHADOW_LIST_NODES_BINDING 4
// and optionally #define AVSM_SHADOW_SET s, the descriptor set (0 when not defined). The
// set may be an ordinary one or a push-descriptor one: the shader does not tell them
// apart. avsm::shadow_lookup_layout() (avsm/shadows.h) gives the matching
// VkDescriptorSetLayoutBinding entries, avsm::ShadowLookupBuffers what to write there.
//
// The maps' layouts are in shared/map_layouts.h. AVSM lookups search a texel's
// depths two levels deep (the course notes' 4-stride search): the last depth of each
// vec4 first, then inside the vec4 that holds the answer.
#ifndef AVSM_SHADOW_LOOKUP_GLSL
#define AVSM_SHADOW_LOOKUP_GLSL

#extension GL_GOOGLE_include_directive : require
#include "avsm/avsm_core.glsl"

#include "shared/capture.h"
#include "shared/map_layouts.h"
#include "shared/area_shadows.h"
#include "shared/shadow.h"

#ifndef AVSM_SHADOW_SET
#define AVSM_SHADOW_SET 0
#endif
#ifdef AVSM_SHADOW_BINDING
#ifndef AVSM_SHADOW_PARAMETERS_BINDING
#define AVSM_SHADOW_PARAMETERS_BINDING AVSM_SHADOW_BINDING
#endif
#ifndef AVSM_SHADOW_ATLAS_BINDING
#define AVSM_SHADOW_ATLAS_BINDING (AVSM_SHADOW_BINDING + 1)
#endif
#ifndef AVSM_SHADOW_LIST_HEADS_BINDING
#define AVSM_SHADOW_LIST_HEADS_BINDING (AVSM_SHADOW_BINDING + 2)
#endif
#ifndef AVSM_SHADOW_LIST_NODES_BINDING
#define AVSM_SHADOW_LIST_NODES_BINDING (AVSM_SHADOW_BINDING + 3)
#endif
#endif
#if !defined(AVSM_SHADOW_PARAMETERS_BINDING) || !defined(AVSM_SHADOW_ATLAS_BINDING) || \
    !defined(AVSM_SHADOW_LIST_HEADS_BINDING) || !defined(AVSM_SHADOW_LIST_NODES_BINDING)
#error shadow_lookup.glsl: define AVSM_SHADOW_BINDING or all four AVSM_SHADOW_*_BINDING before including it
#endif

layout(std430, set = AVSM_SHADOW_SET, binding = AVSM_SHADOW_PARAMETERS_BINDING) readonly buffer ShadowParameters {
  GpuShadow shadows[];
};
layout(std430, set = AVSM_SHADOW_SET, binding = AVSM_SHADOW_ATLAS_BINDING) readonly buffer ShadowMapAtlas {
  vec4 shadow_atlas[];
};
layout(std430, set = AVSM_SHADOW_SET, binding = AVSM_SHADOW_LIST_HEADS_BINDING) readonly buffer ShadowListHeads {
  uint shadow_heads[];
};
layout(std430, set = AVSM_SHADOW_SET, binding = AVSM_SHADOW_LIST_NODES_BINDING) readonly buffer ShadowListNodes {
  CaptureSegment shadow_nodes[];
};

// Paged maps' request bits (shared/pages.h): a pass whose receivers ask for the pages
// they read defines AVSM_SHADOW_PAGE_REQUESTS_BINDING (ShadowInputs::page_requests);
// lookups elsewhere read whatever is resident.
#ifdef AVSM_SHADOW_PAGE_REQUESTS_BINDING
layout(std430, set = AVSM_SHADOW_SET, binding = AVSM_SHADOW_PAGE_REQUESTS_BINDING) buffer ShadowPageRequests {
  uint shadow_page_requests[];
};
#endif

// vec4 i of the map record `s` describes.
vec4 shadow_map_texel(GpuShadow s, uint i) { return shadow_atlas[s.map_offset + i]; }

uint shadow_list_head(GpuShadow s, ivec2 texel) {
  return shadow_heads[s.list_heads_offset + uint(texel.y) * s.resolution + uint(texel.x)];
}

// Node indices are the capture's own, counted from the record's first node.
CaptureSegment shadow_list_node(GpuShadow s, uint i) { return shadow_nodes[s.list_nodes_offset + i]; }

// Whether a walk that has taken `steps` steps goes on to `node`: a list ends at kListEnd,
// and none holds more nodes than the buffer (a bound should one ever be malformed).
bool shadow_list_goes_on(uint node, uint steps) { return node != kListEnd && steps < uint(shadow_nodes.length()); }

float shadow_light_depth(GpuShadow s, vec3 p) { return dot(s.depth_plane.xyz, p) + s.depth_plane.w; }

float shadow_texel_size(GpuShadow s, float depth) { return s.texel_camera.x + s.texel_camera.y * depth; }

// Below this a curve counts as opaque (opaque segments end at exactly 0).
const float kShadowOpaque = 1e-4;

// What a lookup serves: how it filters, and which level it asks a paged map for.
const uint kReceiverPoint = 0u;    // hair, probes: the light's filter
const uint kReceiverSurface = 1u;  // an opaque surface: the soft-shadow kernel too, where the light has one
const uint kReceiverVolume = 2u;   // smoke: a paged map's page_volume_lod_bias levels coarser (soft shadows)

// ---- Paged maps (GpuShadow::page_size != kDenseLayout; shared/pages.h) ----

bool shadow_is_paged(GpuShadow s) { return s.page_size != kDenseLayout; }

// Page-table entry of the page holding `texel` of `level` (kNoPageEntry outside a
// clipmap level's window), and its word (0: absent).
uint shadow_page_entry(GpuShadow s, uint level, ivec2 texel) {
  return page_table_entry(s.resolution, s.page_size, s.page_window, level, uvec2(texel) / s.page_size,
                          s.page_window_centre);
}
uint shadow_page_word(GpuShadow s, uint entry) {
  if (entry == kNoPageEntry) return kPageAbsent;
  return floatBitsToUint(shadow_atlas[s.map_offset + entry / 4u][entry % 4u]);
}

// Marks a page as asked for, where the including pass marks (the bit is read first:
// most receivers ask for pages their neighbours already asked for).
void shadow_request_page(GpuShadow s, uint entry) {
#ifdef AVSM_SHADOW_PAGE_REQUESTS_BINDING
  if (s.page_requests_offset == kNoPageRequests || entry == kNoPageEntry) return;
  uint word = s.page_requests_offset + entry / 32u, bit = 1u << (entry % 32u);
  if ((shadow_page_requests[word] & bit) == 0u) atomicOr(shadow_page_requests[word], bit);
#endif
}

// Where p is in map `s`, in uv (0..1 over the map).
vec2 shadow_map_uv(GpuShadow s, vec3 p) {
  vec4 clip = s.light_from_world * vec4(p, 1.0);
  return clip.xy / clip.w * 0.5 + 0.5;
}

// The world-space steps of one camera pixel across and down at the receiver, where the
// pass knows them (a fragment's derivatives, the resolution pass's depth neighbours;
// look_up_with_pixel_steps()). Zero: unknown. Private to each invocation.
vec3 shadow_pixel_step_x = vec3(0.0), shadow_pixel_step_y = vec3(0.0);
void look_up_with_pixel_steps(vec3 step_x, vec3 step_y) {
  shadow_pixel_step_x = step_x;
  shadow_pixel_step_y = step_y;
}

// A surface the light grazes stretches a texel along the light without end: it asks for
// at most this many levels finer than a texel 1.5 footprints wide. (At 2, the default
// scene at 640x360 matched 98.8% of its lit receivers with 342 pages of 64², against
// 95.7% with 268 at 1.)
const float kPagedStretchLevels = 1.0;

// The smallest singular value of the 2x2 matrix with columns a and b: how short the
// shortest step of the map uv is for a one-pixel step on screen.
float shadow_smallest_stretch(vec2 a, vec2 b) {
  float e = dot(a, a), f = dot(a, b), g = dot(b, b);
  return sqrt(max(0.5 * (e + g - sqrt((e - g) * (e - g) + 4.0 * f * f)), 0.0));
}

// The level a receiver at p (light depth d) asks for, moved by the map's bias (and a
// volume receiver's); fractional (trilinear). A surface whose pixel steps are known asks
// for the coarsest level whose texels are at most kPagedTexelPixels wide on screen at
// their widest (a texel the light stretches across the surface counts at its longest,
// as capture/resolution.h measures): in the default scene at 640x360 that matched 95.7%
// of the lit receivers with 268 pages of 64², where texels one camera pixel's footprint
// wide matched 88.8% with 303. Other receivers (hair, smoke, probes) take texels as wide as a
// camera pixel's footprint at p, facing the camera.
float shadow_paged_lod(GpuShadow s, vec3 p, float d, uint receiver) {
  float pixel_size = distance(p, s.camera_position.xyz) * s.texel_camera.w;
  float bias = s.page_lod_bias + (receiver == kReceiverVolume ? s.page_volume_lod_bias : 0.0);
  float lod = log2(max(pixel_size / max(shadow_texel_size(s, d), 1e-20), 1e-20));
  if (receiver == kReceiverSurface && dot(shadow_pixel_step_x, shadow_pixel_step_x) > 0.0) {
    vec2 uv = shadow_map_uv(s, p);
    float stretch = shadow_smallest_stretch(shadow_map_uv(s, p + shadow_pixel_step_x) - uv,
                                            shadow_map_uv(s, p + shadow_pixel_step_y) - uv);
    lod = max(log2(max(kPagedTexelPixels * stretch * float(s.resolution), 1e-20)),
              lod + log2(kPagedTexelPixels) - kPagedStretchLevels);
  }
  return clamp(lod + bias, 0.0, float(min(s.mip_count - 1u, s.page_fallback_level)));
}

// The finest level at or above `level` whose pages hold all four bilinear taps around
// uv; `mark`: ask for the pages of `level` itself, or, where they lie outside its
// clipmap window, of the finest coarser level whose window holds them. The coarsest
// level is one page that is always resident, so there is always an answer.
uint shadow_paged_resident_level(GpuShadow s, vec2 uv, uint level, bool mark) {
  uint found = s.mip_count - 1u;
  bool ask = mark;
  for (uint k = 0u; k < kMaxPageLevels; ++k) {  // a constant bound: lavapipe miscompiles per-lane ones
    uint l = level + k;
    if (l >= s.mip_count - 1u) break;
    int size = int(max(s.resolution >> l, 1u));
    ivec2 base = ivec2(floor(uv * float(size) - 0.5));
    ivec2 lo = clamp(base, ivec2(0), ivec2(size - 1)), hi = clamp(base + 1, ivec2(0), ivec2(size - 1));
    uint e00 = shadow_page_entry(s, l, lo), e10 = shadow_page_entry(s, l, ivec2(hi.x, lo.y));
    uint e01 = shadow_page_entry(s, l, ivec2(lo.x, hi.y)), e11 = shadow_page_entry(s, l, hi);
    bool in_window = e00 != kNoPageEntry && e10 != kNoPageEntry && e01 != kNoPageEntry && e11 != kNoPageEntry;
    if (ask && in_window) {
      shadow_request_page(s, e00);
      if (e10 != e00) shadow_request_page(s, e10);
      if (e01 != e00) shadow_request_page(s, e01);
      if (e11 != e10 && e11 != e01) shadow_request_page(s, e11);
      ask = false;
    }
    if (shadow_page_word(s, e00) != kPageAbsent && shadow_page_word(s, e10) != kPageAbsent &&
        shadow_page_word(s, e01) != kPageAbsent && shadow_page_word(s, e11) != kPageAbsent) {
      found = l;
      break;
    }
  }
  return found;
}

// Where texel `texel` of `level` lives: the record of its page's slot (a dense map of
// page_size texels, one level; or, for the uncompressed reference, its capture lists)
// and the texel in it. False when the page is absent.
bool shadow_page_texel(GpuShadow s, uint level, ivec2 texel, out GpuShadow page, out ivec2 page_texel) {
  page = s;
  page_texel = texel;
  uint word = shadow_page_word(s, shadow_page_entry(s, level, texel));
  if (word == kPageAbsent) return false;
  page.map_offset = s.page_pool_offset + (word - 1u) * page_slot_vec4s(s.page_size, s.node_count);
  page.list_heads_offset = s.list_heads_offset + (word - 1u) * s.page_size * s.page_size;
  page.list_nodes_offset = s.list_nodes_offset + (word - 1u) * s.page_slot_nodes;
  page.resolution = s.page_size;
  page.mip_count = 1u;
  page_texel = texel % int(s.page_size);
  return true;
}

// The finest level whose page over level-0 texel `texel` is resident, and where that
// level's texel over it is (as shadow_page_texel()): a paged map's stored curve at a
// texel, for texel curves and the viewer's inspector. False when no level holds it.
bool shadow_paged_finest_texel(GpuShadow s, ivec2 texel, out GpuShadow page, out ivec2 page_texel) {
  for (uint level = 0u; level < 32u; ++level) {  // a constant bound: lavapipe miscompiles per-lane ones
    if (level >= s.mip_count) break;
    if (shadow_page_texel(s, level, texel >> level, page, page_texel)) return true;
  }
  return false;
}

bool shadow_filters_with_kernel(GpuShadow s, uint receiver) {
  return receiver == kReceiverSurface && s.kernel != kKernelNone;
}

// The levels of map `s` a lookup at p reads (uv: p in the map, d: its light depth):
// `first`, and when `count` is 2 the next one too, weighted by `blend` (trilinear).
// A paged map reads the finest resident level at or above the receiver's own and asks
// for the receiver's pages (where the including pass marks). A surface's soft-shadow
// kernel filters level 0 alone.
struct ShadowLevels {
  uint first;
  int count;
  float blend;
};

// A paged lookup at lod L + f blends level L + 1 in over the last quarter of the level
// only (f from 0.75 to 1; a band, as engines fade cascades into each other): elsewhere it
// reads, and asks for, one level. Blending across the whole level read twice the taps
// and asked for both levels' pages everywhere. Returns L + 1's weight.
const float kPagedBlendBand = 0.25;
float shadow_paged_coarser_weight(float lod) {
  return clamp((fract(lod) - (1.0 - kPagedBlendBand)) / kPagedBlendBand, 0.0, 1.0);
}

ShadowLevels shadow_lookup_levels(GpuShadow s, vec3 p, vec2 uv, float d, uint receiver) {
  ShadowLevels read = ShadowLevels(0u, 1, 0.0);
  if (shadow_is_paged(s)) {
    // Trilinear between the two levels around the receiver's, in the band before the
    // next level; while one of them is not resident, the finest resident level above
    // stands in alone.
    float lod = shadow_paged_lod(s, p, d, receiver);
    uint level = uint(floor(lod));
    read.blend = shadow_paged_coarser_weight(lod);
    read.count = read.blend > 0.0 && level + 1u < s.mip_count ? 2 : 1;
    uint resident = shadow_paged_resident_level(s, uv, level, true);
    if (read.count == 2 && shadow_paged_resident_level(s, uv, level + 1u, true) != level + 1u) read.count = 1;
    if (resident != level) read.count = 1;
    read.first = resident;
  } else if (!shadow_filters_with_kernel(s, receiver) && s.filter_mode == kFilterTrilinear && s.mip_count > 1u) {  // only techniques with mips have more than one level
    // Level of detail: a camera pixel's footprint at p over a light texel's size there.
    float pixel_size = distance(p, s.camera_position.xyz) * s.texel_camera.w;
    float lod = clamp(log2(max(pixel_size / max(shadow_texel_size(s, d), 1e-20), 1e-20)), 0.0,
                      float(s.mip_count - 1u));
    read.first = uint(floor(lod));
    read.blend = lod - float(read.first);
    read.count = read.first + 1u < s.mip_count ? 2 : 1;
  }
  return read;
}

// The width of the texels a lookup reads, in the map's uv units: the blended level's.
float shadow_read_texel_uv(GpuShadow s, ShadowLevels read) {
  return exp2(float(read.first) + (read.count == 2 ? read.blend : 0.0)) / float(s.resolution);
}

// shadow_texel_transmittance(s, level, texel, d): the light's technique's texel
// lookup, dispatched over the registry (passes/shadows/techniques/registry.h) by the code the
// build generates (cmake/ShadowTechniques.cmake).
#include "techniques_lookup.glsl"

// The taps of the soft-shadow kernel (GpuShadow::kernel) at level 0: texel centres
// over a window of 2r + 2 texels per side around x (the point in texel units).
const int kMaxKernelTaps = int(2u * kMaxKernelRadius + 2u) * int(2u * kMaxKernelRadius + 2u);

// Tap `tap`'s texel and weight: a box of 2r + 1 texels weighs each texel by how much of
// it the box covers (so the weights move smoothly with x); a Gaussian by its value at
// the texel centre.
float shadow_kernel_tap(GpuShadow s, vec2 x, int tap, out ivec2 texel) {
  float radius = float(s.kernel_radius);
  int n = 2 * int(s.kernel_radius) + 2;
  float half_width = radius + 0.5;
  texel = ivec2(floor(x - half_width)) + ivec2(tap % n, tap / n);
  if (s.kernel == kKernelBox) {
    vec2 covered = clamp(min(vec2(texel) + 1.0, x + half_width) - max(vec2(texel), x - half_width), 0.0, 1.0);
    return covered.x * covered.y;
  }
  vec2 offset = (vec2(texel) + 0.5 - x) / (0.5 * radius);
  return exp(-0.5 * dot(offset, offset));
}

// Transmittance from the light `s` describes to world point p. Point: the nearest
// texel of level 0. Bilinear: the four nearest curves evaluated at the point's
// depth and their results weighted (curves cannot be blended). Trilinear: bilinear
// in the two mip levels around the level of detail, blended. The taps run in one
// loop so the texel evaluation is compiled once: inlined per tap, it made the
// shaders that call this (the smoke march above all) several times slower on lavapipe.
// A surface lookup is filtered over the light's kernel (at level 0) when it has one.
float shadow_transmittance_filtered(GpuShadow s, vec3 p, uint receiver) {
  if (s.technique == kShadowNone) return 1.0;
  vec4 clip = s.light_from_world * vec4(p, 1.0);
  if (clip.w <= 0.0) return 1.0;  // behind a spot light: it does not shine there
  vec2 uv = clip.xy / clip.w * 0.5 + 0.5;
  // Outside the map nothing was captured: the point is outside the caster bounds.
  if (any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0)))) return 1.0;
  float d = shadow_light_depth(s, p);

  bool kernel = shadow_filters_with_kernel(s, receiver);  // at level 0: the kernel is the filter
  bool paged = shadow_is_paged(s);
  ShadowLevels read = shadow_lookup_levels(s, p, uv, d, receiver);
  uint level = read.first;
  int levels = read.count;
  float level_blend = read.blend;
  bool bilinear = s.filter_mode != kFilterPoint;
  float result = 0.0;
  for (int l = 0; l < levels; ++l) {
    uint current = level + uint(l);
    int size = int(max(s.resolution >> current, 1u));
    vec2 x = bilinear ? uv * float(size) - 0.5 : uv * float(size);
    ivec2 base = ivec2(floor(x));
    vec2 f = bilinear ? x - vec2(base) : vec2(0.0);
    int n = 2 * int(s.kernel_radius) + 2;
    int taps = kernel ? n * n : (bilinear ? 4 : 1);
    float level_value = 0.0, weights = 0.0;
    for (int tap = 0; tap < kMaxKernelTaps; ++tap) {  // a constant bound: lavapipe miscompiles per-lane ones
      if (tap >= taps) break;
      ivec2 texel;
      float w;
      if (kernel) {
        w = shadow_kernel_tap(s, uv * float(size), tap, texel);
      } else {
        ivec2 offset = ivec2(tap & 1, tap >> 1);
        vec2 w2 = mix(1.0 - f, f, vec2(offset));
        w = w2.x * w2.y;
        texel = base + offset;
      }
      texel = clamp(texel, ivec2(0), ivec2(size - 1));
      // A paged map's texel is in its page's slot: a dense one-level map of its own.
      GpuShadow map = s;
      uint map_level = current;
      if (paged) {
        map_level = 0u;
        if (!shadow_page_texel(s, current, texel, map, texel)) w = 0.0;  // not after a resident level
      }
      if (w > 0.0) level_value += w * shadow_texel_transmittance(map, map_level, texel, d);
      weights += w;
    }
    level_value /= max(weights, 1e-20);
    result += (levels == 1 ? 1.0 : (l == 0 ? 1.0 - level_blend : level_blend)) * level_value;
  }
  return result;
}

float shadow_transmittance(GpuShadow s, vec3 p) { return shadow_transmittance_filtered(s, p, kReceiverPoint); }

// For surfaces: the point moved along its normal (towards the light's side) by a
// few texels, so a surface does not shadow itself through its own blocker segment.
// A paged map's receiver between levels L and L + 1 moves by L's texel times 1 + the
// coarser level's weight: the finer level's texel where it reads that level alone, the
// coarser's where it reads that one alone, and a blend that follows the weights between.
// (The coarser level's texel throughout made the offset double where the lod crosses a
// whole level, a step the seam test saw: tests/passes/light_maps_test.cpp.)
vec3 shadow_surface_point(GpuShadow s, vec3 p, vec3 normal, vec3 to_light) {
  vec3 n = dot(normal, to_light) < 0.0 ? -normal : normal;
  float d = shadow_light_depth(s, p);
  float texel = shadow_texel_size(s, d);
  if (shadow_is_paged(s)) {
    float lod = shadow_paged_lod(s, p, d, kReceiverSurface);
    texel *= exp2(floor(lod)) * (1.0 + shadow_paged_coarser_weight(lod));
    // AVSM nodes keep depth in 16 bits over the light's depth range (shared/map_layouts.h):
    // the offset clears two of those steps too, which the finest levels of a large map's
    // texels do not (a 262144 map over a 150 m avenue: 2.4 mm texels, 3 mm steps, and
    // streaks of self-shadowing on the lit ground without this).
    texel = max(texel, 2.0 * (s.depth_range.y - s.depth_range.x) / 65535.0);
  }
  return p + n * (s.camera_position.w * texel);
}

// The face of a point light's cube that direction d (from the light) leaves through:
// its major axis, in the order +x -x +y -y +z -z (passes/shadows/light_view.cpp builds the faces
// so, each a little wider than 90 degrees, so filtering at a face's edge reads texels
// the face captured).
uint shadow_cube_face(vec3 d) {
  vec3 a = abs(d);
  if (a.x >= a.y && a.x >= a.z) return d.x >= 0.0 ? 0u : 1u;
  if (a.y >= a.z) return d.y >= 0.0 ? 2u : 3u;
  return d.z >= 0.0 ? 4u : 5u;
}

// The cascade of light record `s` (kViewsCascades) at p's camera depth; `count` is 2
// inside the band before a split, where the next cascade is blended in by `blend`.
uint shadow_cascade_at(GpuShadow s, vec3 p, out uint count, out float blend) {
  float depth = dot(p - s.camera_position.xyz, s.view_select.xyz);
  uint split = 0u;
  for (uint k = 0u; k < 3u; ++k)
    if (k + 1u < s.view_count && depth > s.cascade_ends[k]) split = k + 1u;
  float end = s.cascade_ends[split], begin = split == 0u ? 0.0 : s.cascade_ends[split - 1u];
  float band = (end - begin) * s.view_select.w;
  count = 1u;
  blend = 0.0;
  if (split + 1u < s.view_count && band > 0.0 && depth > end - band) {
    blend = clamp((depth - (end - band)) / band, 0.0, 1.0);
    count = 2u;
  }
  return split;
}

// ---- Subsets of an area light's virtual lights (shared/area_shadows.h) ----

// Virtual lights in subset `subset` of `virtual_lights` in subsets of `size`.
uint area_light_subset_count(uint subset, uint virtual_lights, uint size) {
  if (size >= virtual_lights) return virtual_lights;
  uint subsets = area_light_subsets(virtual_lights, size);
  return min(size, (virtual_lights - subset % subsets + subsets - 1u) / subsets);
}

// Member `member` of that subset. The virtual lights are a Hammersley set (index k at x
// = k / K, y = k's bits reversed: passes/shadows/light_view.h); where K and the size are
// powers of two, a subset fixes k's middle bits and takes all high and low ones, so its
// lights spread over the whole light in both directions (a stratum per combination);
// otherwise it takes every subsets-th light from its own.
uint area_light_subset_member(uint subset, uint member, uint virtual_lights, uint size) {
  if (size >= virtual_lights) return member;
  uint subsets = area_light_subsets(virtual_lights, size);
  subset %= subsets;
  bool powers_of_two = (virtual_lights & (virtual_lights - 1u)) == 0u && (size & (size - 1u)) == 0u;
  if (!powers_of_two) return subset + member * subsets;
  uint n = uint(findMSB(virtual_lights)), m = uint(findMSB(size));
  uint high = m / 2u, low = m - high;  // bits of the member along x and along y
  return ((member >> low) << (n - high)) | (subset << low) | (member & ((1u << low) - 1u));
}

// The map record a lookup in light record `record` at p reads first: the light's own
// (one map), the cube face p lies in, its cascade, or its first cluster map.
uint light_map_record_at(uint record, vec3 p) {
  GpuShadow s = shadows[record];
  if (s.views == kViewsCube) return s.first_view + shadow_cube_face(p - s.view_select.xyz);
  if (s.views == kViewsClusters || s.views == kViewsVirtualLights) return s.first_view;
  if (s.views != kViewsCascades) return record;
  uint count;
  float blend;
  return s.first_view + shadow_cascade_at(s, p, count, blend);
}

// Transmittance from the light whose record is shadows[record] to p: its one map, the
// cube face p lies in, the cascade(s) at p's camera depth (blended across a split), the
// product over its cluster maps, or the mean over an area light's virtual lights' maps
// (the share of the light that reaches p: its soft shadow). A surface receiver (kReceiverSurface) is on a
// surface with that normal and is moved off it in each map's own texels. An area light's
// mean may be over subset `subset` of its virtual lights, in subsets of `subset_size`
// (shared/area_shadows.h; one subset of kMaxViewsPerLight: all of them). The maps are
// looked up in one loop so that shadow_transmittance() is compiled once (see above).
float light_record_views_transmittance(uint record, vec3 p, uint receiver, vec3 normal, vec3 to_light, uint subset,
                                       uint subset_size) {
  GpuShadow s = shadows[record];
  if (s.views == kViewsSingle && s.technique == kShadowNone) return 1.0;
  uint first = light_map_record_at(record, p), count = 1u;
  float blend = 0.0;  // cascades: weight of the second map
  if (s.views == kViewsCascades) {
    shadow_cascade_at(s, p, count, blend);
  } else if (s.views == kViewsClusters) {
    count = s.view_count;
  } else if (s.views == kViewsVirtualLights) {
    count = area_light_subset_count(subset, s.view_count, subset_size);
  }
  bool product = s.views == kViewsClusters;
  bool mean = s.views == kViewsVirtualLights;
  float result = product ? 1.0 : 0.0;
  for (uint k = 0u; k < kMaxViewsPerLight; ++k) {
    if (k >= count) break;
    GpuShadow v = s;  // a light with one map: its record is the map's
    if (s.views == kViewsVirtualLights) v = shadows[first + area_light_subset_member(subset, k, s.view_count, subset_size)];
    else if (s.views != kViewsSingle) v = shadows[first + k];
    vec3 q = receiver == kReceiverSurface ? shadow_surface_point(v, p, normal, to_light) : p;
    float t = v.technique == kShadowNone ? 1.0 : shadow_transmittance_filtered(v, q, receiver);
    float weight = mean ? 1.0 / float(count) : (count == 1u ? 1.0 : (k == 0u ? 1.0 - blend : blend));
    result = product ? result * t : result + weight * t;
  }
  return result;
}

float light_record_transmittance(uint record, vec3 p, uint receiver, vec3 normal, vec3 to_light) {
  return light_record_views_transmittance(record, p, receiver, normal, to_light, 0u, kMaxViewsPerLight);
}


// The subset of an area light's virtual lights that light_transmittance() and
// volume_light_transmittance() look up: all of them, unless the pass's main() took a subset
// for its receiver (look_up_media_subset()). Private to each invocation.
uint shadow_area_subset = 0u;
uint shadow_area_subset_size = kMaxViewsPerLight;

// Media receivers (hair vertices, fog froxels, smoke cache cells) look up kMediaAreaLookups
// of an area light's virtual lights: subset `receiver_index` (neighbours take the next ones).
void look_up_media_subset(uint receiver_index) {
  shadow_area_subset = receiver_index;
  shadow_area_subset_size = kMediaAreaLookups;
}

float light_transmittance(uint light_index, vec3 p) {
  return light_record_views_transmittance(light_index, p, kReceiverPoint, vec3(0.0), vec3(0.0), shadow_area_subset,
                                          shadow_area_subset_size);
}

// For smoke: its receivers may read coarser levels of paged maps (page_volume_lod_bias).
float volume_light_transmittance(uint light_index, vec3 p) {
  return light_record_views_transmittance(light_index, p, kReceiverVolume, vec3(0.0), vec3(0.0), shadow_area_subset,
                                          shadow_area_subset_size);
}

// The exact transmittance (the light's capture lists, all nodes) when the frame
// kept them (ShadowOptions::keep_reference), else the technique's own.
float reference_light_transmittance(uint light_index, vec3 p) {
  uint reference = shadows[light_index].reference;
  return light_transmittance(reference == kNoReference ? light_index : reference, p);
}

// The point a surface's lookups in light light_index start from, in its first map's
// texels (a light's record is a copy of its first map's): what the quality pass
// reports against.
vec3 surface_lookup_point(uint light_index, vec3 p, vec3 normal, vec3 to_light) {
  return shadow_surface_point(shadows[light_index], p, normal, to_light);
}

float surface_light_transmittance(uint light_index, vec3 p, vec3 normal, vec3 to_light) {
  return light_record_transmittance(light_index, p, kReceiverSurface, normal, to_light);
}

// The same over subset `subset` of an area light's virtual lights, in subsets of `subset_size`.
float surface_light_subset_transmittance(uint light_index, vec3 p, vec3 normal, vec3 to_light, uint subset,
                                         uint subset_size) {
  return light_record_views_transmittance(light_index, p, kReceiverSurface, normal, to_light, subset, subset_size);
}

#endif
