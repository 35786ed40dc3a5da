#include "fairshape/core/effective_options.h"

namespace fairshape {

namespace {
thread_local EffectiveOptions* active_sink = nullptr;
}

RecordEffectiveOptions::RecordEffectiveOptions(EffectiveOptions& sink) : previous_(active_sink) { active_sink = &sink; }

RecordEffectiveOptions::~RecordEffectiveOptions() { active_sink = previous_; }

EffectiveOptions* RecordEffectiveOptions::current() { return active_sink; }

}  // namespace fairshape
