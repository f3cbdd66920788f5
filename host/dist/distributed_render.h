// One frame rendered by every rank of an MPI job: rank 0 hands tiles out on
// request (and renders too), the others send back each tile they trace, and
// rank 0 alone ends up with the whole frame. The pixels of a tile do not
// depend on who traces it, so the frame is bit-identical to a one-rank
// render on the same kind of device.
#pragma once

#include "dist/mpi_world.h"
#include "gpu/gpu_tracer.h"

#include <cstddef>
#include <vector>

namespace vkray::dist {

struct DistributedStats {
    std::vector<std::size_t> tilesPerRank;  // on rank 0: tiles each rank traced
    double handOutSeconds = 0;  // on rank 0: time its hand-out thread spent receiving and answering
};

// On rank 0 returns the whole frame; on the others, a frame holding only the
// tiles they traced. `progress` (rank 0) hears the rays traced by all ranks.
Frame renderAcrossRanks(const World& world, gpu::GpuTracer& tracer, const Scene& scene,
                        const CameraBasis& camera, const RenderSettings& settings,
                        gpu::GpuRenderStats* stats, const RenderProgress& progress,
                        DistributedStats* distributed = nullptr);

}  // namespace vkray::dist
