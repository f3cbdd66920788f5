#include "dist/distributed_render.h"

#include "dist/job_hand_out.h"
#include "util/error.h"

#include <atomic>
#include <cstdint>
#include <cstring>

namespace vkray::dist {

namespace {

// A tile's pixels as they travel: colour 3, depth 1, normal 3, id 1 (its bits).
constexpr std::size_t kFloatsPerPixel = 8;

std::string pack(const TileRect& tile, const Frame& frame) {
    std::vector<float> values;
    values.reserve(std::size_t(tile.width) * std::size_t(tile.height) * kFloatsPerPixel);
    for (int y = tile.y; y < tile.y + tile.height; ++y) {
        for (int x = tile.x; x < tile.x + tile.width; ++x) {
            const std::size_t i = frame.index(x, y);
            const glm::vec3 c = frame.color[i], n = frame.normal[i];
            float id = 0;
            std::memcpy(&id, &frame.id[i], sizeof id);
            values.insert(values.end(), {c.x, c.y, c.z, frame.depth[i], n.x, n.y, n.z, id});
        }
    }
    return {reinterpret_cast<const char*>(values.data()), values.size() * sizeof(float)};
}

void unpack(const std::string& bytes, const TileRect& tile, Frame& frame) {
    const std::size_t pixels = std::size_t(tile.width) * std::size_t(tile.height);
    if (bytes.size() != pixels * kFloatsPerPixel * sizeof(float))
        throw Error("MPI: a tile came back with " + std::to_string(bytes.size()) +
                    " bytes instead of " +
                    std::to_string(pixels * kFloatsPerPixel * sizeof(float)));
    std::vector<float> values(pixels * kFloatsPerPixel);
    std::memcpy(values.data(), bytes.data(), bytes.size());
    const float* in = values.data();
    for (int y = tile.y; y < tile.y + tile.height; ++y) {
        for (int x = tile.x; x < tile.x + tile.width; ++x, in += kFloatsPerPixel) {
            const std::size_t i = frame.index(x, y);
            frame.color[i] = {in[0], in[1], in[2]};
            frame.depth[i] = in[3];
            frame.normal[i] = {in[4], in[5], in[6]};
            std::memcpy(&frame.id[i], &in[7], sizeof(float));
        }
    }
}

std::string describe(const TileRect& tile) {
    const std::int32_t numbers[4] = {tile.x, tile.y, tile.width, tile.height};
    return {reinterpret_cast<const char*>(numbers), sizeof numbers};
}

TileRect tileOf(const std::string& description) {
    std::int32_t numbers[4] = {};
    if (description.size() != sizeof numbers)
        throw Error("MPI: rank 0 described a tile in " + std::to_string(description.size()) +
                    " bytes");
    std::memcpy(numbers, description.data(), sizeof numbers);
    return {numbers[0], numbers[1], numbers[2], numbers[3]};
}

std::size_t raysIn(const TileRect& tile, const RenderSettings& settings) {
    const int block = settings.block;
    return std::size_t((tile.width + block - 1) / block) *
           std::size_t((tile.height + block - 1) / block) * std::size_t(settings.spp);
}

// Rank 0's schedule: the tiles of rank 0's tile side, taken by its own render
// loop and, through the hand-out, by every other rank.
class HandOutTiles final : public TileSchedule {
public:
    HandOutTiles(const World& world, const RenderSettings& settings)
        : world_(world), settings_(settings), tilesPerRank_(std::size_t(world.size()), 0) {}

    void plan(int width, int height, int tileSide) override {
        tiles_ = tilesOf(width, height, tileSide);
        handOut_.emplace(
            world_, tiles_.size(), [this](std::size_t job) { return describe(tiles_[job]); },
            [this](std::size_t job, int rank, std::string&& pixels) {
                raysDone_ += raysIn(tiles_[job], settings_);
                ++tilesPerRank_[std::size_t(rank)];
                received_.emplace_back(job, std::move(pixels));
            });
    }
    std::optional<TileRect> next() override {
        const std::optional<std::size_t> job = handOut_->take();
        if (!job) return std::nullopt;
        return tiles_[*job];
    }
    void finished(const TileRect& tile, const Frame&) override {
        raysDone_ += raysIn(tile, settings_);
        ++tilesPerRank_[0];
    }

    std::size_t raysDone() const { return raysDone_; }

    // After rank 0's own tiles: waits for the others' last tiles and puts
    // every tile they traced into `frame`.
    void gather(Frame& frame, DistributedStats* stats) {
        handOut_->wait();
        for (const auto& [job, pixels] : received_) unpack(pixels, tiles_[job], frame);
        if (stats) {
            stats->tilesPerRank = tilesPerRank_;
            stats->handOutSeconds = handOut_->answeringSeconds();
        }
    }

private:
    const World& world_;
    RenderSettings settings_;
    std::vector<TileRect> tiles_;
    std::atomic<std::size_t> raysDone_{0};
    std::vector<std::size_t> tilesPerRank_;  // [0]: rank 0's thread; the rest: the answering thread
    std::vector<std::pair<std::size_t, std::string>>
        received_;                       // the answering thread's until wait()
    std::optional<JobHandOut> handOut_;  // last: destroyed first, while the above still live
};

// A worker's schedule: each next() sends the tile just traced to rank 0 and
// asks it for another.
class AskRankZero final : public TileSchedule {
public:
    void plan(int, int, int) override {}
    std::optional<TileRect> next() override {
        std::optional<std::pair<std::size_t, std::string>> done;
        if (traced_) done.emplace(current_, pack(*traced_, *frame_));
        traced_.reset();
        const std::optional<GivenJob> job = askRankZero(done);
        if (!job) return std::nullopt;
        current_ = job->index;
        return tileOf(job->description);
    }
    void finished(const TileRect& tile, const Frame& frame) override {
        traced_ = tile;
        frame_ = &frame;
    }

private:
    std::size_t current_ = 0;
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
    HandOutTiles schedule(world, settings);
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

}  // namespace vkray::dist
