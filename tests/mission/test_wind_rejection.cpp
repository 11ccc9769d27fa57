// Control that holds against a force it is not told about: INDI (control/indi_control.h) and
// the disturbance observer any controller can fly with (control/disturbance_observer.h), on a
// hovering Tello pushed from the side.
#include <doctest/doctest.h>

#include <algorithm>
#include <memory>
#include <optional>
#include <stdexcept>
#include <vector>

#include "control/controllers.h"
#include "flight_test_util.h"
#include "mission/flight_parts.h"
#include "mission/setup.h"

namespace aerobox {
namespace {

using testing::FromFunction;
using testing::RoomAt;

// Pushes the vehicle with a constant force [N] from a time on (a rule that never ends a flight).
class Push : public FlightRule {
 public:
  Push(Simulation* sim, const Vec3& force_W, double from)
      : sim_(sim), force_(force_W), from_(from) {}
  std::optional<FlightStatus> Judge(const FlightMoment& now) override {
    if (now.t >= from_) sim_->SetExternalWrench(force_, Vec3::Zero());
    return std::nullopt;
  }

 private:
  Simulation* sim_;
  Vec3 force_;
  double from_;
};

class Recorder : public FlightObserver {
 public:
  void ControlStep(const TelemetrySample& sample, bool) override { samples.push_back(sample); }
  std::vector<TelemetrySample> samples;
};

// The telemetry of 5 s of hover at 1 m, pushed by `force` [N] from 1 s on; the controller's
// report columns in `columns`.
std::vector<TelemetrySample> PushedHover(const ControllerConfig& config, const Vec3& force,
                                         std::vector<std::string>* columns = nullptr,
                                         const SensorParams& sensors = {}) {
  const QuadParams vehicle;
  const std::unique_ptr<Controller> controller = MakeController(config, vehicle);
  if (columns) *columns = controller->ReportColumns();
  Simulation sim = RoomAt(Vec3(0, 0, 1));
  FlightLoop loop;
  loop.vehicle = &vehicle;
  loop.controller = controller.get();
  loop.control_rate = config.rate;
  loop.inner = config.inner;
  loop.sensors = sensors;
  VehicleWorld world(loop, &sim);
  const Reference hover = FromFunction(5.0, [](double) { return Vec3(0, 0, 1); });
  FlightParams params;
  StandardParts standard(hover, params, loop, &world);
  FlightParts parts = standard.parts();
  Push push(&sim, force, 1.0);
  Recorder recorder;
  parts.rules.insert(parts.rules.begin(), &push);
  parts.observers.push_back(&recorder);
  FlyTrajectory(hover, params, loop, parts);
  return recorder.samples;
}

ControllerConfig Kind(const std::string& kind) {
  ControllerConfig config;
  config.kind = kind;
  return config;
}

// The largest position error [m] over [from, to) s.
double PeakError(const std::vector<TelemetrySample>& samples, double from, double to) {
  double peak = 0.0;
  for (const TelemetrySample& s : samples) {
    if (s.t >= from && s.t < to) peak = std::max(peak, s.position_error);
  }
  return peak;
}

// The report's three columns from `first` at the last sample.
Vec3 Reported(const std::vector<TelemetrySample>& samples, const std::vector<std::string>& columns,
              const std::string& first) {
  const size_t i =
      static_cast<size_t>(std::find(columns.begin(), columns.end(), first) - columns.begin());
  REQUIRE(i + 2 < columns.size());
  const std::vector<double>& r = samples.back().report;
  return Vec3(r[i], r[i + 1], r[i + 2]);
}

const Vec3 kPush(0.1, -0.05, 0.03);  // [N]: 1.4 m/s^2 on the Tello's 80 g

}  // namespace

TEST_CASE("indi holds hover against a step in external force: the error peaks, then decays") {
  std::vector<std::string> columns;
  const std::vector<TelemetrySample> indi = PushedHover(Kind("indi"), kPush, &columns);
  const std::vector<TelemetrySample> se3 = PushedHover(Kind("se3"), kPush);
  REQUIRE(indi.back().t > 4.9);
  CHECK(PeakError(indi, 0.0, 1.0) < 0.002);  // still air: it hovers
  const double peak = PeakError(indi, 1.0, 5.0);
  const double settled = PeakError(indi, 3.0, 5.0);
  // the push moves it by centimetres at most, and two seconds on the error is under 5 mm and a
  // fifth of its peak; se3, which has no integral action, stays off by F / (m k_p), 18 cm
  CHECK(peak < 0.03);
  CHECK(settled < 0.005);
  CHECK(settled < peak / 5);
  CHECK(PeakError(se3, 3.0, 5.0) > 0.1);
  // what the increment met is the push, within 10 %
  CHECK((Reported(indi, columns, "indi_fx") - kPush).norm() < 0.1 * kPush.norm());
}

TEST_CASE("se3 with its position integral: a steady push leaves no steady error") {
  ControllerConfig config = Kind("se3");
  config.se3.position_integral = Vec3(4, 4, 6);
  const std::vector<TelemetrySample> integral = PushedHover(config, kPush);
  const std::vector<TelemetrySample> plain = PushedHover(Kind("se3"), kPush);
  // alone it stays off by F / (m k_p), 18 cm; with the integral (a slow pole at -1 1/s, and
  // growing only while the velocity error is small) the error falls to under a third of that
  // within 4 s of the push (measured: 3.7 cm against 17.7 cm)
  CHECK(PeakError(plain, 4.5, 5.0) > 0.1);
  CHECK(PeakError(integral, 4.5, 5.0) < 0.3 * PeakError(plain, 4.5, 5.0));
}

TEST_CASE("disturbance observer: the estimate reaches a constant push within 0.2 s, se3 holds") {
  ControllerConfig config = Kind("se3");
  config.observer.enabled = true;  // time constant 0.05 s: 95 % in 0.15 s
  std::vector<std::string> columns;
  const std::vector<TelemetrySample> samples = PushedHover(config, kPush, &columns);
  const size_t fx =
      static_cast<size_t>(std::find(columns.begin(), columns.end(), "fext_x") - columns.begin());
  REQUIRE(fx + 2 < columns.size());
  for (const TelemetrySample& s : samples) {
    const Vec3 estimate(s.report[fx], s.report[fx + 1], s.report[fx + 2]);
    if (s.t > 0.5 && s.t < 1.0) CHECK(estimate.norm() < 0.01);  // nothing pushes yet
    if (s.t > 1.2) CHECK((estimate - kPush).norm() < 0.1 * kPush.norm());
  }
  // fed forward, the push no longer holds se3 off (alone: 18 cm, F / (m k_p)); it drifts while
  // it tilts against the push (about 0.3 s, 2.8 cm even with an instant estimate), under 5 cm
  // at its worst, and 2 mm at the end
  CHECK(PeakError(samples, 1.0, 5.0) < 0.05);
  CHECK(PeakError(samples, 3.0, 5.0) < 0.002);
}

TEST_CASE("indi measures the ground truth without sensors, the IMU with them") {
  std::vector<std::string> columns;
  const std::vector<TelemetrySample> truth = PushedHover(Kind("indi"), Vec3::Zero(), &columns);
  const size_t imu =
      static_cast<size_t>(std::find(columns.begin(), columns.end(), "imu") - columns.begin());
  REQUIRE(imu < columns.size());
  CHECK(truth.back().report[imu] == 0.0);

  SensorParams sensors;
  sensors.imu.enabled = true;
  sensors.position.enabled = true;
  const std::vector<TelemetrySample> measured = PushedHover(Kind("indi"), kPush, nullptr, sensors);
  REQUIRE(measured.back().t > 4.9);
  CHECK(measured.back().report[imu] == 1.0);
  // the IMU's first reading is a vehicle held still, not a free fall: no kick at the start.
  // Within 1 cm in the first second (measured 7.8 mm for both, against 3.2 mm for se3, which
  // reads no acceleration: the IMU's turn-on bias, not yet learnt by the filter, reads as a
  // force); with a free fall read first, 11 mm and 54 mm.
  CHECK(PeakError(measured, 0.0, 1.0) < 0.01);
  ControllerConfig observed = Kind("se3");
  observed.observer.enabled = true;
  CHECK(PeakError(PushedHover(observed, kPush, nullptr, sensors), 0.0, 1.0) < 0.01);
  // on the IMU's noisy, biased readings and the filter's estimate it still holds the push off:
  // within 5 cm at worst and 2 cm at the end (the estimate's own error is about 1 cm)
  CHECK(PeakError(measured, 1.0, 5.0) < 0.05);
  CHECK(PeakError(measured, 4.0, 5.0) < 0.02);
}

TEST_CASE("indi on an IMU slower than the controller is refused, naming the key") {
  FlightSetup setup;
  setup.controller.kind = "indi";
  setup.sensors.imu.enabled = true;
  setup.sensors.position.enabled = true;
  setup.sensors.imu.rate = 100.0;  // the controller runs at 250 Hz
  CHECK_THROWS_WITH_AS(setup.Validate(), doctest::Contains("sensors.imu.rate: 100 Hz"),
                       std::invalid_argument);
  setup.sensors.imu.rate = 250.0;
  CHECK_NOTHROW(setup.Validate());
  setup.controller.kind = "se3";  // reads no acceleration: any IMU rate will do
  setup.sensors.imu.rate = 100.0;
  CHECK_NOTHROW(setup.Validate());
}

}  // namespace aerobox
