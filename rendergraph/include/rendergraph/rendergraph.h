#pragma once
// Umbrella header of the frame-graph planning core.
#include <rendergraph/graph.h>
#include <rendergraph/memory_model.h>
#include <rendergraph/plan.h>
#include <rendergraph/types.h>
#include <rendergraph/usage.h>
#include <rendergraph/vk_names.h>
