#include "thread_policy.hpp"

#include <algorithm>
#include <utility>

namespace softstep {
namespace {

// The median of the first n of a few samples (an insertion sort: gcc 12 reports a false
// -Warray-bounds inside std::sort on a four-element array).
template <std::size_t N>
double median_of(std::array<double, N> v, int n) {
  for (int i = 1; i < n; ++i) {
    for (int j = i; j > 0 && v[static_cast<std::size_t>(j)] < v[static_cast<std::size_t>(j - 1)];
         --j) {
      std::swap(v[static_cast<std::size_t>(j)], v[static_cast<std::size_t>(j - 1)]);
    }
  }
  const auto at = [&](int i) { return v[static_cast<std::size_t>(i)]; };
  return n % 2 == 1 ? at(n / 2) : 0.5 * (at(n / 2 - 1) + at(n / 2));
}

// A probe step this much slower than the settled count's steps has lost: the other count is
// not going to win by the block's median (a held core makes two-thread steps 2-50x slower).
constexpr double kClearlyLosing = 1.5;
// The warm-up step after a switch may pay for records moving between caches; only far beyond
// that (a descheduled thread waiting at barriers) does it end a probe.
constexpr double kWarmupClearlyLosing = 3.0;

}  // namespace

void ThreadPolicy::switch_count() {
  current_ = 1 - current_;
  sampled_ = 0;
  warmed_ = false;
  ++switches_;
}

// The probe's block is complete (or lost early): keep the faster count.
void ThreadPolicy::decide_probe() {
  const int probe = current_, settled = 1 - current_;
  probing_ = false;
  settled_steps_ = 0;
  if (estimate_[settled] == 0.0) {  // the very first block: now measure the other count
    probing_ = true;
    switch_count();
    return;
  }
  if (estimate_[probe] < estimate_[settled]) {
    probe_interval_ = kFirstProbeInterval;  // the probe won: stay on it
    sampled_ = 0;                           // its block goes on as the settled one's
    return;
  }
  probe_interval_ = std::min(2 * probe_interval_, kLongestProbeInterval);
  switch_count();
}

void ThreadPolicy::record(double ms, bool untimed) {
  if (untimed) return;
  const int other = 1 - current_;
  if (!warmed_) {
    warmed_ = true;
    if (probing_ && estimate_[other] > 0.0 && ms > kWarmupClearlyLosing * estimate_[other]) {
      estimate_[current_] = ms;
      decide_probe();
    }
    return;
  }
  samples_[static_cast<std::size_t>(sampled_ % kTrialSteps)] = ms;
  ++sampled_;
  const int n = std::min(sampled_, kTrialSteps);
  if (probing_) {
    if (estimate_[other] > 0.0 && ms > kClearlyLosing * estimate_[other]) {
      estimate_[current_] = ms;
      decide_probe();
    } else if (sampled_ == kTrialSteps) {
      estimate_[current_] = median_of(samples_, n);
      decide_probe();
    }
    return;
  }
  // Settled: the estimate follows the recent steps, so that a core taken by another process
  // shows up as this count getting slower than the other's last measure.
  estimate_[current_] = median_of(samples_, n);
  ++settled_steps_;
  const bool due = settled_steps_ >= probe_interval_;
  const bool overtaken = n == kTrialSteps && estimate_[current_] > kClearlyLosing * estimate_[other];
  if (due || overtaken) {
    probing_ = true;
    switch_count();
  }
}

}  // namespace softstep
