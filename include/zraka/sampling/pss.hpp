#pragma once
// Primary sample space (Kelemen, Szirmay-Kalos, Antal and Csonka 2002), for chapter 6.4.
//
// A path tracer turns a vector of uniform numbers u = (u_0, u_1, ...) into a path and its
// contribution. Metropolis light transport walks a Markov chain over these vectors: each step
// proposes a new vector, either a *large step* (every number drawn afresh: an independent
// sample) or a *small step* (every number moved a little, u_i + N(0, sigma^2), wrapped into
// [0, 1)). The vector is as long as the path needs: numbers are made when first asked for.
//
// Lazily: a number the current path does not ask for is not moved at every step. It remembers
// the step it was last brought up to date; when asked for, it is redrawn if a large step was
// accepted since, and otherwise moved by the n small steps it missed at once (the sum of n normal
// steps is one normal step with n sigma^2). A rejected proposal restores what it changed.
//
// The chain's own choices (large or small, the normal steps, acceptance) come from its own
// counter-based stream, so a chain is the same for a seed whatever else runs beside it.
#include <zraka/core/error.hpp>
#include <zraka/core/rng.hpp>

#include <cmath>
#include <cstdint>
#include <numbers>
#include <vector>

namespace zraka {

struct pss_options {
  double sigma = 0.01;             // standard deviation of a small step (Kelemen et al.: ~1/64 .. 1/100)
  double large_step_prob = 0.3;    // probability of a large step
};

// Refuses what the mutations cannot use, by name (programs call it before any other work).
inline void check_pss_options(const pss_options& opt) {
  if (!(opt.sigma > 0 && opt.sigma < 1)) throw error("metropolis: the small-step sigma must be in (0, 1)");
  if (!(opt.large_step_prob >= 0 && opt.large_step_prob <= 1))
    throw error("metropolis: the large-step probability must be in [0, 1]");
}

// [listing primary-sample-space]
class primary_sample_space final : public number_source {
 public:
  // `start`: the stream whose numbers are the first state (a bootstrap sample's stream, so the
  // chain starts on the path the bootstrap chose); `chain`: the stream of the chain's choices.
  primary_sample_space(const rng& start, const rng& chain, const pss_options& opt)
      : start_(start), chain_(chain), opt_(opt) {
    check_pss_options(opt);
  }

  // Before the first start_step, the numbers are the start state's (step 0). Each call begins a
  // proposal: a large step with probability large_step_prob, else a small one.
  void start_step() {
    ++step_;
    large_ = chain_.uniform() < opt_.large_step_prob;
  }
  bool large_step() const { return large_; }

  std::uint32_t number(std::uint32_t d) override {
    if (d >= x_.size()) grow(d);
    coordinate& c = x_[d];
    if (c.updated < step_) {  // bring it up to date, remembering the old value in case of rejection
      c.saved_value = c.value, c.saved_updated = c.updated, c.dirty = step_;
      if (large_) {
        c.value = chain_.uniform();
      } else {
        if (c.updated < last_large_) {  // a large step was accepted since: this number is new there
          c.value = chain_.uniform();
          c.updated = last_large_;
        }
        const double n = double(step_ - c.updated);  // small steps missed, this one included
        c.value = wrap(c.value + normal() * opt_.sigma * std::sqrt(n));
      }
      c.updated = step_;
    }
    return std::uint32_t(c.value * 0x1p32);  // c.value < 1, so below 2^32; the start's word exactly
  }

  // A number of the chain's own stream (for the acceptance test).
  double uniform() { return chain_.uniform(); }

  void accept() {
    if (large_) last_large_ = step_;
  }
  // Restores every number the proposal changed and takes the step back: steps count accepted
  // proposals, so a number the path did not ask for has moved once per accepted small step, as
  // it would have if every number were moved at every step.
  void reject() {
    for (coordinate& c : x_)
      if (c.dirty == step_) c.value = c.saved_value, c.updated = c.saved_updated, c.dirty = 0;
    --step_;
  }

 private:
  struct coordinate {
    double value = 0;
    std::uint64_t updated = 0;   // the step this value belongs to
    double saved_value = 0;      // before the current proposal
    std::uint64_t saved_updated = 0;
    std::uint64_t dirty = 0;     // the step that last changed it
  };
  void grow(std::uint32_t d) {
    if (d > (1u << 20)) throw error("metropolis: a path asked for more than 2^20 random numbers");
    while (x_.size() <= d) {  // new numbers: the start stream's, as of step 0
      rng s = start_;
      s.skip_to(std::uint32_t(x_.size()));
      x_.push_back({double(s.next_u32()) * 0x1p-32, 0, 0, 0, 0});  // exactly the start's word
    }
  }
  static double wrap(double v) {
    v -= std::floor(v);
    return v < 1 ? v : 0;  // -1e-17 - floor(...) rounds to 1
  }
  double normal() {  // Box-Muller, one of the pair
    const double u1 = 1 - chain_.uniform(), u2 = chain_.uniform();  // u1 in (0, 1]
    return std::sqrt(-2 * std::log(u1)) * std::cos(2 * std::numbers::pi * u2);
  }

  rng start_, chain_;
  pss_options opt_;
  std::vector<coordinate> x_;
  std::uint64_t step_ = 0, last_large_ = 0;
  bool large_ = false;
};
// [end]

}  // namespace zraka
