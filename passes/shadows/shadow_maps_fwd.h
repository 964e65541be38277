#pragma once
// Forward declaration for camera passes that take shadow inputs (passes/shadows/shadow_maps.h).
namespace avsm::passes {
struct ShadowInputs;
}
