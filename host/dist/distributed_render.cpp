#include "dist/distributed_render.h"

#include "scene/error.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <cstring>
#include <memory>
#include <mutex>
#include <thread>

#if VKRAY_WITH_MPI
#include <mpi.h>
#endif

namespace vkray::dist {

#if VKRAY_WITH_MPI

namespace {

// The conversation, per worker: "ask" (carrying the tile it just traced, if
// any) and "give" (the next tile, or none), until there is none.
constexpr int kAsk = 1, kGive = 2;
constexpr int kFloatsPerPixel = 8;  // colour 3, depth 1, normal 3, id 1 (its bits)

// Open MPI's blocking calls spin on their core, which here is the core the
// rank renders on (mpirun binds each rank to its own): poll, and sleep
// between polls instead.
void waitForMessage(int source, int tag, MPI_Status& status) {
    for (auto pause = std::chrono::microseconds(20);; pause = std::min(pause * 2, std::chrono::microseconds(1000))) {
        int arrived = 0;
        MPI_Iprobe(source, tag, MPI_COMM_WORLD, &arrived, &status);
        if (arrived) return;
        std::this_thread::sleep_for(pause);
    }
}

std::size_t raysIn(const TileRect& tile, const RenderSettings& settings) {
    const int block = settings.block;
    return std::size_t((tile.width + block - 1) / block) *
           std::size_t((tile.height + block - 1) / block) * std::size_t(settings.spp);
}

// A tile's pixels after a one-int header (its index in the hand-out list).
std::vector<float> pack(std::int32_t index, const TileRect& tile, const Frame& frame) {
    std::vector<float> message(1 + std::size_t(tile.width) * std::size_t(tile.height) * kFloatsPerPixel);
    std::memcpy(message.data(), &index, sizeof index);
    float* out = message.data() + 1;
    for (int y = tile.y; y < tile.y + tile.height; ++y) {
        for (int x = tile.x; x < tile.x + tile.width; ++x) {
            const std::size_t i = frame.index(x, y);
            const glm::vec3 c = frame.color[i], n = frame.normal[i];
            *out++ = c.x, *out++ = c.y, *out++ = c.z, *out++ = frame.depth[i];
            *out++ = n.x, *out++ = n.y, *out++ = n.z;
            std::memcpy(out++, &frame.id[i], sizeof(float));
        }
    }
    return message;
}

void unpack(const float* in, const TileRect& tile, Frame& frame) {
    for (int y = tile.y; y < tile.y + tile.height; ++y) {
        for (int x = tile.x; x < tile.x + tile.width; ++x) {
            const std::size_t i = frame.index(x, y);
            frame.color[i] = {in[0], in[1], in[2]};
            frame.depth[i] = in[3];
            frame.normal[i] = {in[4], in[5], in[6]};
            std::memcpy(&frame.id[i], &in[7], sizeof(float));
            in += kFloatsPerPixel;
        }
    }
}

// Rank 0's schedule: one list of tiles, taken from by its own render loop
// and, through a thread that answers the other ranks, by everyone else.
class HandOut final : public TileSchedule {
public:
    HandOut(const World& world, const RenderSettings& settings)
        : state_(std::make_shared<State>()) {
        state_->workers = world.size() - 1;
        state_->settings = settings;
        state_->tilesPerRank.assign(std::size_t(world.size()), 0);
    }
    ~HandOut() override {
        // Unwinding from an error or Ctrl-C: the thread may wait on a worker
        // for ever; the caller ends the job (World::abort), and the thread
        // keeps its state alive until then.
        if (thread_.joinable()) thread_.detach();
    }

    void plan(int width, int height, int tileSide) override {
        state_->tiles = tilesOf(width, height, tileSide);
        thread_ = std::thread([state = state_] { state->answerWorkers(); });
    }
    std::optional<TileRect> next() override {
        const std::optional<std::size_t> index = state_->take();
        if (!index) return std::nullopt;
        return state_->tiles[*index];
    }
    void finished(const TileRect& tile, const Frame&) override {
        state_->raysDone += raysIn(tile, state_->settings);
        ++state_->tilesPerRank[0];
    }

    std::size_t raysDone() const { return state_->raysDone; }

    // After rank 0's own tiles: waits for the workers' last tiles and puts
    // every worker tile into `frame`.
    void gather(Frame& frame, DistributedStats* stats) {
        thread_.join();
        for (const auto& [index, pixels] : state_->received)
            unpack(pixels.data() + 1, state_->tiles[index], frame);
        if (stats) {
            stats->tilesPerRank = state_->tilesPerRank;
            stats->handOutSeconds = state_->busySeconds;
        }
    }

private:
    struct State {
        int workers = 0;
        RenderSettings settings;
        std::vector<TileRect> tiles;
        std::mutex mutex;
        std::size_t nextTile = 0;
        std::atomic<std::size_t> raysDone{0};
        std::vector<std::size_t> tilesPerRank;  // the [0] entry: rank 0's thread only
        std::vector<std::pair<std::size_t, std::vector<float>>> received;
        double busySeconds = 0;

        std::optional<std::size_t> take() {
            const std::lock_guard lock(mutex);
            if (nextTile == tiles.size()) return std::nullopt;
            return nextTile++;
        }

        void answerWorkers() {
            for (int working = workers; working > 0;) {
                MPI_Status status;
                waitForMessage(MPI_ANY_SOURCE, kAsk, status);
                const auto start = std::chrono::steady_clock::now();
                int count = 0;
                MPI_Get_count(&status, MPI_FLOAT, &count);
                std::vector<float> message(std::size_t(std::max(count, 1)));
                MPI_Recv(message.data(), count, MPI_FLOAT, status.MPI_SOURCE, kAsk, MPI_COMM_WORLD,
                         MPI_STATUS_IGNORE);
                std::int32_t done = -1;
                std::memcpy(&done, message.data(), sizeof done);
                if (done >= 0 && std::size_t(done) < tiles.size()) {
                    const TileRect& tile = tiles[std::size_t(done)];
                    if (std::size_t(count) ==
                        1 + std::size_t(tile.width) * std::size_t(tile.height) * kFloatsPerPixel) {
                        raysDone += raysIn(tile, settings);
                        ++tilesPerRank[std::size_t(status.MPI_SOURCE)];
                        received.emplace_back(std::size_t(done), std::move(message));
                    }
                }
                std::int32_t answer[5] = {-1, 0, 0, 0, 0};
                if (const std::optional<std::size_t> index = take()) {
                    const TileRect& tile = tiles[*index];
                    answer[0] = std::int32_t(*index);
                    answer[1] = tile.x, answer[2] = tile.y, answer[3] = tile.width,
                    answer[4] = tile.height;
                } else {
                    --working;
                }
                MPI_Send(answer, 5, MPI_INT32_T, status.MPI_SOURCE, kGive, MPI_COMM_WORLD);
                busySeconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
            }
        }
    };

    std::shared_ptr<State> state_;
    std::thread thread_;
};

// A worker's schedule: each next() sends the tile just traced to rank 0 and
// asks it for another.
class AskRankZero final : public TileSchedule {
public:
    void plan(int, int, int) override {}
    std::optional<TileRect> next() override {
        const std::vector<float> message =
            traced_ ? pack(current_, *traced_, *frame_) : pack(-1, TileRect{}, Frame());
        MPI_Send(message.data(), int(message.size()), MPI_FLOAT, 0, kAsk, MPI_COMM_WORLD);
        std::int32_t answer[5] = {};
        MPI_Status status;
        waitForMessage(0, kGive, status);
        MPI_Recv(answer, 5, MPI_INT32_T, 0, kGive, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
        traced_.reset();
        if (answer[0] < 0) return std::nullopt;
        current_ = answer[0];
        return TileRect{answer[1], answer[2], answer[3], answer[4]};
    }
    void finished(const TileRect& tile, const Frame& frame) override {
        traced_ = tile;
        frame_ = &frame;
    }

private:
    std::int32_t current_ = -1;
    std::optional<TileRect> traced_;
    const Frame* frame_ = nullptr;
};

}  // namespace

Frame renderAcrossRanks(const World& world, gpu::GpuTracer& tracer, const Scene& scene,
                        const CameraBasis& camera, const RenderSettings& settings,
                        gpu::GpuRenderStats* stats, const RenderProgress& progress,
                        DistributedStats* distributed) {
    if (world.rank() != 0) {
        AskRankZero schedule;
        return tracer.render(scene, camera, settings, stats, nullptr, &schedule);
    }
    HandOut schedule(world, settings);
    // The display shows every rank's rays, counted as their tiles come in.
    std::size_t raysTotal = 0;
    const RenderProgress allRanks = [&](std::size_t, std::size_t total) {
        raysTotal = total;
        return !progress || progress(schedule.raysDone(), total);
    };
    Frame frame = tracer.render(scene, camera, settings, stats, allRanks, &schedule);
    schedule.gather(frame, distributed);
    if (progress) progress(schedule.raysDone(), raysTotal);
    return frame;
}

#else

Frame renderAcrossRanks(const World&, gpu::GpuTracer&, const Scene&, const CameraBasis&,
                        const RenderSettings&, gpu::GpuRenderStats*, const RenderProgress&,
                        DistributedStats*) {
    throw Error("this vkray was built without MPI support");
}

#endif

}  // namespace vkray::dist
