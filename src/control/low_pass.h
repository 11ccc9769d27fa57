// Second-order Butterworth low-pass filters, discrete (the bilinear transform with the cutoff
// prewarped), for the measurements an incremental controller differences and compares: the
// same filter on every signal keeps them in step (Tal and Karaman 2021, section IV).
#pragma once

#include <cmath>
#include <optional>

namespace aerobox {

template <typename T>
class LowPass2 {
 public:
  // `cutoff` [Hz] below half the sampling `rate` [Hz].
  LowPass2(double cutoff, double rate) {
    const double k = std::tan(3.14159265358979323846 * cutoff / rate);
    const double norm = 1.0 / (1.0 + std::sqrt(2.0) * k + k * k);
    b0_ = k * k * norm;
    a1_ = 2.0 * (k * k - 1.0) * norm;
    a2_ = (1.0 - std::sqrt(2.0) * k + k * k) * norm;
  }

  // The next sample in, the filtered value out; the first sample starts the filter at rest
  // there.
  const T& Update(const T& x) {
    if (!y1_) {
      x1_ = x2_ = x;
      y1_ = y2_ = x;
    }
    const T y = b0_ * (x + 2.0 * x1_ + x2_) - a1_ * *y1_ - a2_ * *y2_;
    x2_ = x1_;
    x1_ = x;
    y2_ = y1_;
    y1_ = y;
    return *y1_;
  }
  const T& value() const { return *y1_; }  // after an Update
  bool started() const { return y1_.has_value(); }

 private:
  double b0_ = 0, a1_ = 0, a2_ = 0;
  T x1_{}, x2_{};
  std::optional<T> y1_, y2_;
};

}  // namespace aerobox
