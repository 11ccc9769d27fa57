// The learning environments' core for aerobox.envs: an EnvBatch with numpy arrays in and out,
// the GIL released while the worlds step.
#include "python/envs_binding.h"

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <cmath>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "envs/env_batch.h"
#include "envs/swarm_world.h"
#include "mission/swarm.h"
#include "python/py_params.h"
#include "python/seams.h"
#include "render/renderer.h"

namespace py = pybind11;

namespace aerobox {
namespace {

class EnvCore {
 public:
  EnvCore(const py::dict& kwargs, int worlds, int threads, std::string who) : who_(std::move(who)) {
    EnvParams params;
    ParamsFromKwargs(kwargs, who_, &params);
    if (worlds < 1) throw py::value_error(who_ + ": num_envs must be at least 1");
    try {
      batch_ = std::make_unique<EnvBatch>(params, worlds, threads);
    } catch (const std::invalid_argument& e) {
      throw py::value_error(who_ + ": " + e.what());
    }
  }

  int size() const { return batch_->size(); }
  int observation_size() const { return batch_->params().ObservationSize(); }
  int action_size() const { return batch_->params().ActionSize(); }
  // The vehicle as RotorPy's quad_params dict (what a controller flying the policy needs).
  py::dict quad_params() const { return python::VehicleDict(batch_->params().Vehicle()); }

  std::vector<std::string> observation_names() const { return batch_->params().ObservationNames(); }
  std::vector<std::string> reward_terms() const { return batch_->params().RewardTermNames(); }

  py::array_t<float> Reset(const std::vector<std::optional<std::uint64_t>>& seeds,
                           const py::object& options) {
    const EnvOptions parsed = Options(options);
    py::array_t<float> obs({size(), observation_size()});
    float* out = obs.mutable_data();
    try {
      py::gil_scoped_release free;
      batch_->Reset(seeds, out, parsed);
    } catch (const std::invalid_argument& e) {
      throw py::value_error(who_ + ": reset: " + e.what());
    }
    return obs;
  }

  py::array_t<float> ResetSome(const std::vector<int>& indices) {
    py::array_t<float> obs({static_cast<int>(indices.size()), observation_size()});
    float* out = obs.mutable_data();
    try {
      py::gil_scoped_release free;
      batch_->ResetSome(indices, out);
    } catch (const std::out_of_range& e) {
      throw py::index_error(who_ + ": reset: " + e.what());
    }
    return obs;
  }

  py::tuple Step(const py::array_t<double, py::array::c_style | py::array::forcecast>& actions) {
    if (actions.ndim() != 2 || actions.shape(0) != size() || actions.shape(1) != action_size()) {
      throw py::value_error(who_ + ": step: the actions have shape " + Shape(actions) +
                            ", expected (" + std::to_string(size()) + ", " +
                            std::to_string(action_size()) + ")");
    }
    const int n = size();
    const int n_terms = batch_->term_count();
    py::array_t<float> obs({n, observation_size()});
    py::array_t<double> rewards(n), terms({n, n_terms});
    py::array_t<bool> terminated(n), truncated(n);
    float* o = obs.mutable_data();
    double* r = rewards.mutable_data();
    double* t = terms.mutable_data();
    auto* te = reinterpret_cast<std::uint8_t*>(terminated.mutable_data());
    auto* tr = reinterpret_cast<std::uint8_t*>(truncated.mutable_data());
    const double* a = actions.data();
    try {
      py::gil_scoped_release free;
      batch_->Step(a, o, r, te, tr, t);
    } catch (const std::invalid_argument& e) {
      throw py::value_error(who_ + ": step: " + e.what());
    }
    return py::make_tuple(obs, rewards, terminated, truncated, terms);
  }

  // World i's picture from the chase camera, (height, width, 3) uint8.
  py::array_t<std::uint8_t> Render(int i, int width, int height) {
    if (i < 0 || i >= size())
      throw py::index_error(who_ + ": render: no world " + std::to_string(i));
    Simulation& shown = batch_->Showing(i);  // with the rigid backend, one shared scene
    if (!renderer_ || rendered_ != &shown) {
      renderer_.reset();
      renderer_ = std::make_unique<Renderer>(&shown, RenderSettings(width, height, Quality::kFast));
      rendered_ = &shown;
    }
    Overlay overlay;
    EnvWorld& world = batch_->world(i);
    overlay.goal = world.task().Reference(world.time());
    Image image;
    renderer_->Render(CameraSpec{}, overlay, &image);
    py::array_t<std::uint8_t> out({image.height, image.width, 3});
    std::copy(image.rgb.begin(), image.rgb.end(), out.mutable_data());
    return out;
  }

 private:
  // reset's options: a dict of "start" and "target", each three numbers [m] (or None).
  EnvOptions Options(const py::object& options) const {
    EnvOptions parsed;
    if (options.is_none()) return parsed;
    if (!py::isinstance<py::dict>(options)) {
      throw py::value_error(who_ + ": reset: options " + py::repr(options).cast<std::string>() +
                            ": expected a dict (keys start, target) or None");
    }
    const std::vector<std::string> keys = {"start", "target"};
    for (const auto item : options.cast<py::dict>()) {
      const std::string key = py::str(item.first);
      std::optional<Vec3>* slot = key == "start"    ? &parsed.start
                                  : key == "target" ? &parsed.target
                                                    : nullptr;
      if (slot == nullptr) {
        const std::string near = NearestName(key, keys);
        throw py::value_error(who_ + ": reset: unknown option '" + key + "'" +
                              (near.empty() ? "" : "; did you mean '" + near + "'?") +
                              " (options: start, target)");
      }
      if (item.second.is_none()) continue;
      std::vector<double> xyz;
      try {
        xyz = item.second.cast<std::vector<double>>();
      } catch (const py::cast_error&) {
      }
      if (xyz.size() != 3) {
        throw py::value_error(who_ + ": reset: options['" + key + "'] " +
                              py::repr(item.second).cast<std::string>() +
                              ": expected three numbers [m]");
      }
      *slot = Vec3(xyz[0], xyz[1], xyz[2]);
    }
    return parsed;
  }

  static std::string Shape(const py::array& a) {
    std::string s = "(";
    for (py::ssize_t i = 0; i < a.ndim(); ++i) {
      s += (i ? ", " : "") + std::to_string(a.shape(i));
    }
    return s + (a.ndim() == 1 ? ",)" : ")");
  }

  std::string who_;
  std::unique_ptr<EnvBatch> batch_;
  std::unique_ptr<Renderer> renderer_;
  const Simulation* rendered_ = nullptr;
};

// Several agents in one world (aerobox.marl): numpy in and out, the GIL released while it steps.
class SwarmCore {
 public:
  SwarmCore(const py::dict& kwargs, int agents, const std::vector<double>& room, std::string who)
      : who_(std::move(who)) {
    EnvParams params;
    ParamsFromKwargs(kwargs, who_, &params);
    if (room.size() != 6) throw py::value_error(who_ + ": room: expected six numbers [m]");
    try {
      world_ = std::make_unique<SwarmWorld>(
          params, agents, Aabb{Vec3(room[0], room[1], room[2]), Vec3(room[3], room[4], room[5])});
    } catch (const std::invalid_argument& e) {
      throw py::value_error(who_ + ": " + e.what());
    }
    action_size_ = params.ActionSize();
  }

  int agents() const { return world_->agents(); }
  int action_size() const { return action_size_; }
  double time() const { return world_->time(); }
  double vehicle_radius() const { return VehicleRadius(world_->vehicle()); }  // [m]
  py::dict quad_params() const { return python::VehicleDict(world_->vehicle()); }

  void Reset(const py::array_t<double, py::array::c_style | py::array::forcecast>& starts) {
    if (starts.ndim() != 2 || starts.shape(0) != agents() || starts.shape(1) != 3) {
      throw py::value_error(who_ + ": reset: the starts need shape (" + std::to_string(agents()) +
                            ", 3)");
    }
    std::vector<Vec3> points;
    for (int i = 0; i < agents(); ++i)
      points.emplace_back(starts.at(i, 0), starts.at(i, 1), starts.at(i, 2));
    world_->Reset(points);
  }

  // Each agent's action, or a row of NaN for an agent out of the game (rotors off); returns what
  // each touched ("" nothing).
  std::vector<std::string> Step(
      const py::array_t<double, py::array::c_style | py::array::forcecast>& actions) {
    if (actions.ndim() != 2 || actions.shape(0) != agents() || actions.shape(1) != action_size_) {
      throw py::value_error(who_ + ": step: the actions need shape (" + std::to_string(agents()) +
                            ", " + std::to_string(action_size_) + ")");
    }
    std::vector<const double*> rows;
    for (int i = 0; i < agents(); ++i) {
      const double* row = actions.data(i, 0);
      rows.push_back(std::isnan(row[0]) ? nullptr : row);
    }
    py::gil_scoped_release free;
    return world_->Step(rows);
  }

  // Every agent's state, one row each: x, y, z, vx, vy, vz, qw, qx, qy, qz, wx, wy, wz (world
  // position and velocity, body-to-world attitude, body rates).
  py::array_t<double> States() const {
    py::array_t<double> out({agents(), 13});
    for (int i = 0; i < agents(); ++i) {
      const State s = world_->state(i);
      double* row = out.mutable_data(i, 0);
      const double values[13] = {s.p_W.x(), s.p_W.y(),  s.p_W.z(),  s.v_W.x(),  s.v_W.y(),
                                 s.v_W.z(), s.q_WB.w(), s.q_WB.x(), s.q_WB.y(), s.q_WB.z(),
                                 s.w_B.x(), s.w_B.y(),  s.w_B.z()};
      std::copy(values, values + 13, row);
    }
    return out;
  }

 private:
  std::string who_;
  std::unique_ptr<SwarmWorld> world_;
  int action_size_ = 4;
};

// The parameters' reference (key, unit, default, range, meaning), for the documentation.
py::list EnvKeys() {
  py::list rows;
  for (const KeyRow& row : KeyRows<EnvParams>("")) {
    rows.append(py::make_tuple(row.key, row.unit, row.value, row.range, row.meaning));
  }
  return rows;
}

}  // namespace

void BindEnvs(py::module_& m) {
  py::class_<EnvCore>(m, "EnvCore")
      .def(py::init<const py::dict&, int, int, std::string>(), py::arg("params"), py::arg("worlds"),
           py::arg("threads"), py::arg("who"))
      .def_property_readonly("size", &EnvCore::size)
      .def_property_readonly("observation_size", &EnvCore::observation_size)
      .def_property_readonly("action_size", &EnvCore::action_size)
      .def_property_readonly("quad_params", &EnvCore::quad_params)
      .def_property_readonly("observation_names", &EnvCore::observation_names)
      .def_property_readonly("reward_terms", &EnvCore::reward_terms)
      .def("reset", &EnvCore::Reset, py::arg("seeds"), py::arg("options") = py::none())
      .def("reset_some", &EnvCore::ResetSome, py::arg("worlds"))
      .def("step", &EnvCore::Step, py::arg("actions"))
      .def("render", &EnvCore::Render, py::arg("world"), py::arg("width"), py::arg("height"));
  py::class_<SwarmCore>(m, "SwarmCore")
      .def(py::init<const py::dict&, int, const std::vector<double>&, std::string>(),
           py::arg("params"), py::arg("agents"), py::arg("room"), py::arg("who"))
      .def_property_readonly("agents", &SwarmCore::agents)
      .def_property_readonly("action_size", &SwarmCore::action_size)
      .def_property_readonly("time", &SwarmCore::time)
      .def_property_readonly("vehicle_radius", &SwarmCore::vehicle_radius)
      .def_property_readonly("quad_params", &SwarmCore::quad_params)
      .def("reset", &SwarmCore::Reset, py::arg("starts"))
      .def("step", &SwarmCore::Step, py::arg("actions"))
      .def("states", &SwarmCore::States);
  m.def("env_keys", &EnvKeys);
}

}  // namespace aerobox
