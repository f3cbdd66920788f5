#include "app/view_command.h"

#include "app/camera_navigation.h"
#include "app/commands.h"
#include "app/view_events.h"
#include "app/view_window.h"
#include "app/watch.h"
#include "gpu/context.h"
#include "gpu/gpu_tracer.h"
#include "gpu/presenter.h"
#include "image/aov_images.h"
#include "image/image_io.h"
#include "image/metrics.h"
#include "numerics/agreement.h"
#include "reference/reference_tracer.h"
#include "util/error.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <deque>
#include <filesystem>
#include <limits>
#include <memory>
#include <mutex>
#include <optional>
#include <ostream>
#include <set>
#include <thread>

namespace vkray {

namespace fs = std::filesystem;

namespace {

using Clock = std::chrono::steady_clock;

std::string fixed(double value, int digits) {
    char text[64];
    std::snprintf(text, sizeof text, "%.*f", digits, value);
    return text;
}

std::string firstLine(const std::string& text) {
    return text.substr(0, text.find('\n'));
}

bool sameCamera(const Camera& a, const Camera& b) {
    return a.eye == b.eye && a.look == b.look && a.up == b.up && a.fovDegrees == b.fovDegrees;
}

// The CPU reference of one view, rendered on a thread of its own; the
// window goes on answering meanwhile.
class CpuReference {
public:
    ~CpuReference() { stop(); }

    void start(const Scene& scene, const CameraBasis& camera, const RenderSettings& settings,
               int threads) {
        stop();
        stopping_ = false;
        finished_ = false;
        raysDone_ = 0;
        raysTotal_ = 1;
        frame_.reset();
        error_.clear();
        running_ = true;
        thread_ = std::thread([this, scene, camera, settings, threads] {
            try {
                reference::ReferenceOptions options;
                options.threads = threads;
                options.progress = [this](std::size_t done, std::size_t total) {
                    raysDone_ = done;
                    raysTotal_ = std::max<std::size_t>(total, 1);
                    return !stopping_.load();
                };
                Frame frame = reference::render(scene, camera, settings, options);
                const std::lock_guard<std::mutex> lock(mutex_);
                frame_ = std::move(frame);
            } catch (const Interrupted&) {
            } catch (const std::exception& e) {
                const std::lock_guard<std::mutex> lock(mutex_);
                error_ = e.what();
            }
            finished_ = true;
            ViewWindow::wake();
        });
    }
    void stop() {
        stopping_ = true;
        if (thread_.joinable()) thread_.join();
        running_ = false;
    }
    // Running and not yet taken.
    bool running() const { return running_; }
    double fraction() const { return double(raysDone_.load()) / double(raysTotal_.load()); }
    // Once it has finished: its frame (or its error), and it stops running.
    bool take(std::optional<Frame>& frame, std::string& error) {
        if (!running_ || !finished_) return false;
        stop();
        const std::lock_guard<std::mutex> lock(mutex_);
        frame = std::move(frame_);
        error = error_;
        return true;
    }

private:
    std::thread thread_;
    std::atomic<bool> stopping_{false}, finished_{false};
    bool running_ = false;
    std::atomic<std::size_t> raysDone_{0}, raysTotal_{1};
    std::mutex mutex_;
    std::optional<Frame> frame_;
    std::string error_;
};

// The tiles of one pass less those already in the picture: a pass cut
// short by a reload that failed goes on where it stopped, rather than
// adding a sample twice to the tiles it had done.
class RemainingTiles final : public TileSchedule {
public:
    void clear() { done_.clear(); }
    bool none() const { return done_.empty(); }  // the pass has not started
    void absorbed(const TileRect& tile) { done_.insert({tile.x, tile.y}); }
    void plan(int width, int height, int tileSide) override {
        tiles_ = tilesOf(width, height, tileSide);
        next_ = 0;
    }
    std::optional<TileRect> next() override {
        while (next_ < tiles_.size() && done_.count({tiles_[next_].x, tiles_[next_].y})) ++next_;
        if (next_ == tiles_.size()) return std::nullopt;
        return tiles_[next_++];
    }
    void finished(const TileRect&, const Frame&) override {}

private:
    std::set<std::pair<int, int>> done_;  // their corners
    std::vector<TileRect> tiles_;
    std::size_t next_ = 0;
};

class ViewSession {
public:
    ViewSession(const Options& o, const std::vector<ViewEvent>& script, std::ostream& out,
                std::ostream& err)
        : o_(o),
          out_(out),
          err_(err),
          shaders_(shaderDirectoryFor(o)),
          window_(o.width, o.height, "vkray view " + o.scenePath),
          context_(
              gpu::ContextOptions{o.device, o.validation, 0, window_.surfaceExtensions(), true}),
          tracer_(context_, gpuRenderOptions(o)),
          presenter_(context_, shaders_, window_.surfaceMaker(), o.width, o.height),
          passes_(viewProgression(o.width, o.height, o.spp, o.seed)) {
        tracer_.setTileListener([this](const gpu::TracedTile& tile) {
            presenter_.absorb(tile);
            remaining_.absorbed(tile.rect);
        });
        script_.assign(script.begin(), script.end());
        settings_.threshold = float(o.failThreshold.value_or(kCheckFailThreshold));
        out_ << "device: " << context_.device().name << " (" << context_.device().type << ", "
             << context_.device().driverName << " " << context_.device().driverInfo << ")\n";
    }

    int run() {
        load(true);
        watchInputs();
        while (!quit_ && !stopRequested()) {
            handle(window_.events());
            if (reloadDue_ || (watcher_ && watcher_->changed())) reload();
            collectCpuReference();
            runScript();
            if (quit_ || screenshotDue()) break;
            if (rendering()) {
                runPass();
            } else {
                show();
                handle(window_.events(0.05));
            }
        }
        if (o_.validation && context_.validationMessages() > 0)
            setError("--validation: " + std::to_string(context_.validationMessages()) +
                     " validation message(s), printed above");
        if (!errorStanding().empty()) {
            err_ << "vkray: view: ended with an error standing (above)\n";
            return 1;
        }
        return 0;
    }

private:
    // ---- the scene and its reloads ------------------------------------------
    void load(bool first) {
        try {
            Scene scene = loadSceneFor(o_, err_);
            const Camera camera = chooseCamera(scene, o_);
            // Refused here, at its place; --precision auto chooses from the
            // scene's own camera at each load, not at each move of the view.
            const CameraBasis basis = makeCameraBasis(camera, o_.width, o_.height);
            precision_ = precisionInForce(scene, basis, o_, out_, err_).precision;
            tracer_.setPrecision(precision_);
            if (first || !sameCamera(camera, sceneCamera_)) camera_ = camera;
            sceneCamera_ = camera;
            scene_ = std::move(scene);
            sceneError_.clear();
            restart();
            if (!first) out_ << "reloaded " << o_.scenePath << std::endl;
        } catch (const Error& e) {
            report(e.what());
            sceneError_ = e.what();
            if (!first)
                err_ << "vkray: kept the last good image; fix the error and save to retry\n";
        }
        updateTitle();
    }

    void reload() {
        reloadDue_ = false;
        load(false);
        ++reloads_;
        watchInputs();
    }

    // One watcher for the whole session, so that a save made while a reload
    // reads the files is seen and reloads again; each reload adds what the
    // scene now reads (a new include, a new mesh file).
    void watchInputs() {
        if (!watcher_) watcher_ = std::make_unique<FileWatcher>();
        for (const std::string& file : sceneInputs(o_)) watcher_->watchFile(file);
        watcher_->watchFolder(shaders_);
        out_ << "watching " << o_.scenePath << " and " << shaders_ << std::endl;
    }

    void report(const std::string& message) {
        printError(Error(message), err_);
        err_.flush();
    }
    // The render's error (a shader that does not compile, a device failure).
    void setError(const std::string& message) {
        report(message);
        renderError_ = message;
        updateTitle();
    }
    std::string errorStanding() const { return sceneError_.empty() ? renderError_ : sceneError_; }

    // ---- the progression -----------------------------------------------------
    void restart() {
        remaining_.clear();
        nextPass_ = 0;
        passesSinceRestart_ = 0;
        failed_ = false;
        cpuValid_ = false;
        difference_.reset();
        presenter_.setVerdicts({});
        cpu_.stop();
        if (wantsCpu()) startCpu();
    }

    bool rendering() const { return scene_ && !failed_ && nextPass_ < passes_.size(); }
    bool complete() const { return nextPass_ == passes_.size(); }

    void runPass() {
        const ViewPass& pass = passes_[nextPass_];
        if (remaining_.none()) presenter_.beginPass(pass.fresh, pass.settings.firstSample == 0);
        interrupted_ = false;
        tileDone_ = 0;
        tileTotal_ = 1;
        try {
            const CameraBasis basis = makeCameraBasis(camera_, o_.width, o_.height);
            gpu::GpuRenderStats stats;
            tracer_.render(
                *scene_, basis, pass.settings, &stats,
                [this](std::size_t done, std::size_t total) { return betweenTiles(done, total); },
                &remaining_);
            remaining_.clear();
            ++nextPass_;
            ++passesSinceRestart_;
            ++passesDone_;
            mrays_ = stats.renderSeconds > 0 ? double(stats.rays) / stats.renderSeconds / 1e6 : 0;
            renderError_.clear();
            show();
            out_ << "pass " << nextPass_ << "/" << passes_.size() << ": " << pass.name << ", "
                 << fixed(stats.renderSeconds, 3) << " s, " << fixed(mrays_, 2) << " Mrays/s"
                 << std::endl;
            if (complete()) compareWithCpu();
        } catch (const Interrupted&) {
            // A camera change, a reload or a quit: the main loop takes it from here.
        } catch (const Error& e) {
            failed_ = true;
            setError(e.what());
            err_ << "vkray: kept the last good image; fix the error and save to retry\n";
            show();
        }
    }

    // The tracer's progress: after each tile, the window is brought up to
    // date and its input handled; false cancels the pass.
    bool betweenTiles(std::size_t done, std::size_t total) {
        tileDone_ = done;
        tileTotal_ = std::max<std::size_t>(total, 1);
        // The window follows the tiles at 10 frames a second at most: a
        // composition of the whole view costs more than a small tile.
        if (done > 0 && Clock::now() - lastShown_ >= std::chrono::milliseconds(100))
            show();
        else
            updateTitle();
        handle(window_.events());
        if (watcher_ && watcher_->changed()) reloadDue_ = true;
        if (stopRequested()) quit_ = true;
        if (reloadDue_ || interrupted_ || quit_) {
            interrupted_ = false;
            return false;
        }
        return true;
    }

    // ---- input -------------------------------------------------------------
    void handle(const std::vector<ViewEvent>& events) {
        for (const ViewEvent& e : events) apply(e);
    }

    void apply(const ViewEvent& e) {
        switch (e.kind) {
        case ViewEvent::Kind::Drag:
            moveCamera(e.rightButton ? pan(camera_, e.dx, -e.dy, o_.height)
                                     : orbit(camera_, -e.dx * kOrbitDegreesPerPixel,
                                             e.dy * kOrbitDegreesPerPixel));
            break;
        case ViewEvent::Kind::Wheel: moveCamera(zoom(camera_, e.steps)); break;
        case ViewEvent::Kind::Key: key(e.key); break;
        default: break;  // the waits are the script's (runScript)
        }
    }

    void key(const std::string& k) {
        if (k == "q" || k == "esc")
            quit_ = true;
        else if (k == "r")
            moveCamera(sceneCamera_);
        else if (k == "p")
            out_ << cameraLine(camera_) << std::endl;
        else if (k == "1")
            settings_.view = gpu::View::Color;
        else if (k == "2")
            settings_.view = gpu::View::Depth;
        else if (k == "3")
            settings_.view = gpu::View::Normal;
        else if (k == "4")
            settings_.view = gpu::View::ObjectId;
        else if (k == "c") {
            showCpu_ = !showCpu_;
            if (showCpu_ && !cpuValid_ && !cpu_.running()) startCpu();
        } else if (k == "d") {
            showDifference_ = !showDifference_;
            if (showDifference_ && !cpuValid_ && !cpu_.running()) startCpu();
            if (showDifference_) compareWithCpu();
        } else if (k == "s")
            save(nextFreeName());
        show();
    }

    void moveCamera(const Camera& camera) {
        try {
            makeCameraBasis(camera, o_.width, o_.height);
        } catch (const Error&) {
            return;  // a degenerate camera (the eye on the look point): the move is not made
        }
        if (sameCamera(camera, camera_)) return;
        camera_ = camera;
        interrupted_ = true;
        restart();
    }

    // The script's events in order, up to a wait that is not yet over. They
    // are taken between passes only, so that a script gives the same images
    // however fast the machine is.
    void runScript() {
        while (!script_.empty() && !quit_) {
            const ViewEvent& e = script_.front();
            if (e.kind == ViewEvent::Kind::WaitPass) {
                if (!waiting_) passesAtWait_ = passesDone_;
                waiting_ = true;
                if (passesDone_ == passesAtWait_ && rendering()) return;
            } else if (e.kind == ViewEvent::Kind::WaitCpu) {
                if (cpu_.running()) return;
            } else if (e.kind == ViewEvent::Kind::WaitReload) {
                if (!waiting_) {
                    reloadsAtWait_ = reloads_;
                    out_ << "waiting for a reload" << std::endl;
                }
                waiting_ = true;
                if (reloads_ == reloadsAtWait_) return;
            } else {
                apply(e);
            }
            waiting_ = false;
            script_.pop_front();
        }
    }

    // --frames N, once the script is done: the progression has made N passes
    // since it last started (or all of them, or cannot go on).
    bool screenshotDue() {
        if (o_.frames == 0 || !script_.empty()) return false;
        const std::size_t target = std::min<std::size_t>(std::size_t(o_.frames), passes_.size());
        if (passesSinceRestart_ < target && rendering()) return false;
        if (cpu_.running() && (showCpu_ || showDifference_)) return false;
        if (std::size_t(o_.frames) > passes_.size())
            out_ << "--frames " << o_.frames << ": the progression has " << passes_.size()
                 << " passes, all made\n";
        if (!o_.screenshotPath.empty()) save(o_.screenshotPath);
        return true;
    }

    // ---- the CPU reference and the difference -----------------------------
    bool wantsCpu() const { return showCpu_ || showDifference_; }

    void startCpu() {
        if (!scene_) return;
        const int threads =
            o_.threads > 0 ? o_.threads : int(std::max(1u, std::thread::hardware_concurrency()));
        cpu_.start(*scene_, makeCameraBasis(camera_, o_.width, o_.height),
                   RenderSettings{o_.width, o_.height, 1, o_.spp, o_.seed}, threads);
    }

    void collectCpuReference() {
        std::optional<Frame> frame;
        std::string error;
        if (!cpu_.take(frame, error)) return;
        if (!frame) {
            setError("the CPU reference failed: " + error);
            return;
        }
        presenter_.setCpuReference(*frame);
        cpuDepth_ = finiteRange(frame->depth);
        cpuColor_ = colorImage(*frame);
        cpuFrame_ = std::move(*frame);
        cpuValid_ = true;
        out_ << "cpu reference ready" << std::endl;
        compareWithCpu();
        show();
    }

    // The GPU's picture against the CPU reference. Complete, by `render
    // --check`'s rule on the colours (numerics/agreement.h; the picture has
    // no AOVs on the host, so ids, depth and normals are the reference's);
    // before, the pixels over the threshold.
    void compareWithCpu() {
        if (!showDifference_ || !cpuValid_) return;
        const Image picture = presenter_.pictureColor();
        if (!complete() || !scene_) {
            const CompareResult result =
                compareImages(picture, cpuColor_, {settings_.threshold, kCheckFailPercent});
            difference_ = result.pixelsOverThreshold;
            presenter_.setVerdicts({});
            out_ << "difference: " << result.pixelsOverThreshold << " of " << result.pixelCount
                 << " pixels with error > " << settings_.threshold
                 << " (the GPU's progression is not complete)" << std::endl;
            return;
        }
        Frame gpu = cpuFrame_;
        for (std::size_t i = 0; i < gpu.pixelCount(); ++i)
            gpu.color[i] = {picture.pixels[3 * i], picture.pixels[3 * i + 1],
                            picture.pixels[3 * i + 2]};
        AgreementOptions rule;
        rule.colorThreshold = settings_.threshold;
        rule.threads = o_.threads;
        const RenderSettings settings{o_.width, o_.height, 1, o_.spp, o_.seed};
        const Agreement a = judgeAgreement(*scene_, makeCameraBasis(camera_, o_.width, o_.height),
                                           settings, precision_, gpu, cpuFrame_, rule);
        difference_ = a.colors;
        std::vector<gpu::ShownVerdict> verdicts(a.pixels);
        for (std::size_t i = 0; i < a.pixels; ++i)
            verdicts[i] = a.verdicts[i] == PixelVerdict::SetAside ? gpu::ShownVerdict::SetAside
                          : a.verdicts[i] == PixelVerdict::Unexplained
                              ? gpu::ShownVerdict::Unexplained
                              : gpu::ShownVerdict::Same;
        presenter_.setVerdicts(verdicts);
        out_ << "difference: " << a.colors << " of " << a.pixels << " pixels with error > "
             << settings_.threshold << "; " << a.setAside << " set aside, " << a.unexplained
             << " unexplained (the margin rule, " << precisionName(precision_) << ")" << std::endl;
    }

    static std::pair<float, float> finiteRange(const std::vector<float>& depths) {
        float lo = std::numeric_limits<float>::infinity(), hi = -lo;
        for (const float d : depths)
            if (std::isfinite(d)) {
                lo = std::min(lo, d);
                hi = std::max(hi, d);
            }
        return lo <= hi ? std::make_pair(lo, hi) : std::make_pair(0.0f, 0.0f);
    }

    // ---- the window ------------------------------------------------------
    gpu::ViewSettings viewNow() const {
        gpu::ViewSettings s = settings_;
        s.cpuReference = showCpu_ && cpuValid_;
        if (showDifference_) s.view = cpuValid_ ? gpu::View::Difference : gpu::View::Color;
        const auto [lo, hi] = s.cpuReference ? cpuDepth_ : presenter_.depthRange();
        s.depthNear = lo;
        s.depthFar = hi;
        return s;
    }

    void show() {
        shown_ = viewNow();
        presenter_.show(shown_);
        lastShown_ = Clock::now();
        updateTitle();
    }

    void updateTitle() {
        std::string title = "vkray view " + fs::path(o_.scenePath).filename().string();
        if (!passes_.empty()) {
            const std::size_t at = std::min(nextPass_, passes_.size() - 1);
            title += " | pass " + std::to_string(at + 1) + "/" + std::to_string(passes_.size()) +
                     " " + passes_[at].name;
            if (rendering())
                title += " (" +
                         std::to_string(int(100.0 * double(tileDone_) / double(tileTotal_))) +
                         " %)";
        }
        title += " | " + fixed(mrays_, 2) + " Mrays/s | " + context_.device().name;
        const gpu::ViewSettings& s = shown_;
        if (s.view == gpu::View::Depth)
            title += " | depth " + fixed(s.depthNear, 3) + " .. " + fixed(s.depthFar, 3);
        if (s.view == gpu::View::Normal) title += " | normals";
        if (s.view == gpu::View::ObjectId) title += " | object ids";
        if (showCpu_)
            title += cpuValid_
                         ? " | CPU reference"
                         : " | CPU reference " + std::to_string(int(100 * cpu_.fraction())) + " %";
        if (showDifference_) {
            if (!cpuValid_)
                title += " | difference: CPU reference " +
                         std::to_string(int(100 * cpu_.fraction())) + " %";
            else if (difference_)
                title += " | difference: " + std::to_string(*difference_) + " pixels over " +
                         fixed(s.threshold, 3);
        }
        if (!errorStanding().empty()) title += " | ERROR " + firstLine(errorStanding());
        window_.setTitle(title);
    }

    // `s`: the view as shown, written atomically.
    void save(const std::string& path) {
        show();
        try {
            writeImage(path, presenter_.shownImage());
            out_ << "wrote " << path << std::endl;
        } catch (const Error& e) {
            setError(e.what());
        }
    }

    std::string nextFreeName() const {
        const std::string stem = fs::path(o_.scenePath).stem().string();
        for (int n = 1;; ++n) {
            const std::string name = stem + "-" + std::to_string(n) + ".png";
            if (!fs::exists(name)) return name;
        }
    }

    const Options& o_;
    std::ostream& out_;
    std::ostream& err_;
    std::string shaders_;
    ViewWindow window_;  // before the context: the surface goes before the window
    gpu::Context context_;
    gpu::GpuTracer tracer_;
    gpu::Presenter presenter_;
    std::unique_ptr<FileWatcher> watcher_;
    std::vector<ViewPass> passes_;
    RemainingTiles remaining_;  // of the pass in flight

    std::optional<Scene> scene_;
    Camera sceneCamera_, camera_;
    std::string sceneError_, renderError_;  // the errors standing, shown in the title

    std::size_t nextPass_ = 0, passesSinceRestart_ = 0, passesDone_ = 0;
    bool failed_ = false;       // the progression stopped on an error until the next change
    bool interrupted_ = false;  // the camera moved: the pass in flight is cancelled
    bool reloadDue_ = false;
    bool quit_ = false;
    std::size_t tileDone_ = 0, tileTotal_ = 1;
    double mrays_ = 0;
    Clock::time_point lastShown_;

    gpu::ViewSettings settings_, shown_;
    bool showCpu_ = false, showDifference_ = false;
    CpuReference cpu_;
    bool cpuValid_ = false;  // the CPU reference shown is of the current camera and scene
    Image cpuColor_;
    Frame cpuFrame_;
    Precision precision_ = Precision::Robust;
    std::pair<float, float> cpuDepth_{0, 0};
    std::optional<std::size_t> difference_;

    std::deque<ViewEvent> script_;
    bool waiting_ = false;
    std::size_t passesAtWait_ = 0, reloads_ = 0, reloadsAtWait_ = 0;
};

}  // namespace

std::vector<ViewPass> viewProgression(int width, int height, int spp, std::uint32_t seed) {
    std::vector<ViewPass> passes;
    for (const int block : {16, 8, 4, 2})
        passes.push_back({RenderSettings{width, height, block, 1, seed}, true,
                          "block " + std::to_string(block)});
    for (int k = 0; k < spp; ++k) {
        RenderSettings settings{width, height, 1, spp, seed};
        settings.firstSample = k;
        settings.sampleCount = 1;
        passes.push_back(
            {settings, k == 0,
             spp == 1 ? std::string("block 1")
                      : "block 1, sample " + std::to_string(k + 1) + " of " + std::to_string(spp)});
    }
    return passes;
}

int runView(const Options& options, std::ostream& out, std::ostream& err) {
    // The script is read first: its mistakes are told before a window opens.
    const std::vector<ViewEvent> script =
        options.eventsPath.empty() ? std::vector<ViewEvent>{} : readViewEvents(options.eventsPath);
    if (!options.screenshotPath.empty())
        requireWritableFolder(options.screenshotPath, "--screenshot");
    const StopOnSignal closeOnCtrlC;
    ViewSession session(options, script, out, err);
    return session.run();
}

}  // namespace vkray
