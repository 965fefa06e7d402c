#include "app/render_session.h"

#include "gpu/vulkan_error.h"
#include "film/state_file.h"

#include <cstdio>
#include <sstream>
#include <stdexcept>

namespace pt {
namespace {

std::string formatSeconds(double v) {
    std::ostringstream s;
    s.precision(9);
    s << v;
    return s.str();
}

} // namespace

RenderSession::RenderSession(
    const RenderOptions& o, const Scene& scene, const Job& job, Renderer& renderer, ImageMetadata base)
    : o_(o), job_(job), renderer_(renderer), identity_(renderIdentity(o, scene, job)) {
    if (!o.samples.empty()) {
        range_ = parseSampleRange(o.samples);
        renderer.setFirstSample(range_->begin);
    }
    if (!o.resume.empty()) {
        ImageMetadata saved;
        const AccumulationState state = readStateExr(o.resume, saved);
        if (const std::string why = identityMismatch(identity_, saved); !why.empty())
            throw std::runtime_error(o.resume + ": cannot resume: it is a checkpoint of another render: " + why);
        const uint32_t begin = range_ ? range_->begin : 0;
        if (state.samples.begin != begin || (range_ && state.samples.end > range_->end))
            throw std::runtime_error(o.resume + ": cannot resume: it holds samples " + state.samples.describe() +
                                     ", this render is " + (range_ ? range_->describe() : "from sample 0"));
        renderer.loadState(state);
        resumedSpp_ = state.spp;
        if (auto it = saved.find("seconds"); it != saved.end())
            priorSeconds_ = std::strtod(it->second.c_str(), nullptr);
    }
    identity_.addTo(base);
    // --resume without --checkpoint keeps checkpointing into the file it resumed from.
    const std::string path = !o.checkpoint.empty() ? o.checkpoint : o.resume;
    checkpointer_.emplace(path, o.checkpointEvery, std::move(base), priorSeconds_);
}

ProgressiveResult RenderSession::run(const std::function<ProgressiveResult(const ProgressiveTarget&)>& render) {
    ProgressiveTarget target = job_.target;
    if (range_) {
        target.spp = range_->count();
        target.seconds = 0;
    }
    target.afterPass = [this](double seconds) {
        checkpointer_->afterPass(renderer_, seconds);
        return interrupted() == 0;
    };
    try {
        return render(target);
    } catch (const VulkanError& e) {
        // The device's memory can no longer be trusted: save the latest snapshot instead.
        std::string saved = "; nothing rendered was saved (no snapshot yet; see --checkpoint-every)";
        if (const AccumulationState* latest = checkpointer_->latest(); latest && latest->spp > 0) {
            const bool checkpointed = checkpointer_->writeLatest();
            checkpointer_->writeLatestTo(job_.output);
            saved = "; saved the " + std::to_string(latest->spp) + " spp rendered before it to " +
                    job_.output.string() + (checkpointed ? " and " + checkpointer_->path().string() : "") +
                    " (continue with --resume)";
        }
        throw std::runtime_error(std::string(e.what()) + saved);
    }
}

void RenderSession::finish(double seconds) {
    if (interrupted() || !checkpointer_->path().empty()) checkpointer_->save(renderer_, seconds);
}

void RenderSession::addMetadata(ImageMetadata& meta, double seconds) const {
    identity_.addTo(meta);
    meta["seconds"] = formatSeconds(priorSeconds_ + seconds);
    meta["samples"] =
        SampleRange{renderer_.firstSample(), renderer_.firstSample() + renderer_.samplesPerPixel()}.describe();
}

} // namespace pt
