#include "sim/simulation.h"

#include <cstring>
#include <string>

#include "common/error.h"
#include "sim/mujoco_messages.h"
#include "vehicle/model_names.h"
#include "vehicle/quad_params.h"

namespace aerobox {
namespace {

struct VfsDeleter {
  void operator()(mjVFS* vfs) const {
    mj_deleteVFS(vfs);
    delete vfs;
  }
};

int RequireId(const mjModel* model, mjtObj type, const std::string& name,
              const std::string& source) {
  const int id = mj_name2id(model, type, name.c_str());
  if (id < 0) {
    throw InputError({source, 0}, name,
                     "the model has no element of this name (not an aerobox scene?)");
  }
  return id;
}

// The vehicles of a model: the lone one ("quad"), or every body called "<name>/quad".
std::vector<std::string> VehicleNames(const mjModel* model) {
  if (mj_name2id(model, mjOBJ_BODY, model_names::kBody) >= 0) return {""};
  const std::string suffix = std::string("/") + model_names::kBody;
  std::vector<std::string> names;
  for (int b = 0; b < model->nbody; ++b) {
    const char* name = mj_id2name(model, mjOBJ_BODY, b);
    const std::string body = name != nullptr ? name : "";
    if (body.size() > suffix.size() &&
        body.compare(body.size() - suffix.size(), suffix.size(), suffix) == 0) {
      names.push_back(body.substr(0, body.size() - suffix.size()));
    }
  }
  return names.empty() ? std::vector<std::string>{""} : names;  // "" names the missing body
}

}  // namespace

Simulation Simulation::FromXml(const std::string& xml, const std::string& source,
                               const std::vector<std::string>& vehicles) {
  InstallMujocoMessageHandlers();
  // mjVFS is about 2 MB: keep it on the heap
  std::unique_ptr<mjVFS, VfsDeleter> vfs(new mjVFS);
  mj_defaultVFS(vfs.get());
  constexpr const char* kName = "scene.xml";
  if (mj_makeEmptyFileVFS(vfs.get(), kName, static_cast<int>(xml.size())) != 0) {
    throw InputError({source, 0}, "", "MuJoCo could not hold the model text in memory");
  }
  const int index = mj_findFileVFS(vfs.get(), kName);
  std::memcpy(vfs->filedata[index], xml.data(), xml.size());
  char error[1024] = "";
  MjModelPtr model(mj_loadXML(kName, vfs.get(), error, sizeof(error)));
  if (!model) throw InputError({source, 0}, "MJCF", error);
  const std::vector<std::string> names = vehicles.empty() ? VehicleNames(model.get()) : vehicles;
  return Simulation(std::move(model), source, names);
}

Simulation Simulation::FromFile(const std::string& path) {
  InstallMujocoMessageHandlers();
  char error[1024] = "";
  MjModelPtr model(mj_loadXML(path.c_str(), nullptr, error, sizeof(error)));
  if (!model) throw InputError({path, 0}, "MJCF", error);
  const std::vector<std::string> names = VehicleNames(model.get());
  return Simulation(std::move(model), path, names);
}

Simulation::Simulation(MjModelPtr model, const std::string& source,
                       const std::vector<std::string>& vehicles)
    : model_(std::move(model)) {
  data_.reset(mj_makeData(model_.get()));
  if (vehicles.empty()) throw InputError({source, 0}, "", "a world needs a vehicle");
  const auto resets = std::make_shared<long>(0);
  for (const std::string& name : vehicles) {
    vehicles_.push_back(
        std::make_unique<MujocoVehicle>(model_.get(), data_.get(), name, source, resets));
  }
  mj_forward(model_.get(), data_.get());
}

Simulation Simulation::Clone() const {
  std::vector<std::string> names;
  for (const auto& v : vehicles_) names.push_back(v->name());
  return Simulation(MjModelPtr(mj_copyModel(nullptr, model_.get())), "a copy of the scene", names);
}

void Simulation::StepWorld() { mj_step(model_.get(), data_.get()); }

MujocoVehicle::MujocoVehicle(mjModel* model, mjData* data, std::string name,
                             const std::string& source, std::shared_ptr<long> resets)
    : model_(model), data_(data), name_(std::move(name)), resets_(std::move(resets)) {
  const auto of = [this](const std::string& element) { return model_names::Of(name_, element); };
  body_id_ = RequireId(model_, mjOBJ_BODY, of(model_names::kBody), source);
  const int joint = model_->body_jntadr[body_id_];
  if (joint < 0 || model_->jnt_type[joint] != mjJNT_FREE) {
    throw InputError({source, 0}, of(model_names::kBody), "the vehicle body has no free joint");
  }
  qpos_adr_ = model_->jnt_qposadr[joint];
  qvel_adr_ = model_->jnt_dofadr[joint];
  for (int i = 0; i < kNumRotors; ++i) {
    const std::string actuator = of(model_names::ThrustActuator(i));
    actuator_ids_[i] = RequireId(model_, mjOBJ_ACTUATOR, actuator, source);
    // MuJoCo 2.2 keeps activations only for actuators with dynamics, and those come last
    // in the actuator list, so actuator k owns act[k - (nu - na)]
    act_adr_[i] = actuator_ids_[i] - (model_->nu - model_->na);
    if (model_->actuator_dyntype[actuator_ids_[i]] != mjDYN_FILTER || act_adr_[i] < 0) {
      throw InputError({source, 0}, actuator, "the rotor actuator has no motor-lag filter");
    }
  }
  made_.mass = model_->body_mass[body_id_];
  for (int k = 0; k < 3; ++k) made_.inertia[k] = model_->body_inertia[3 * body_id_ + k];
  for (int i = 0; i < kNumRotors; ++i) {
    const int a = actuator_ids_[i];
    made_.gain[i] = model_->actuator_gainprm[mjNGAIN * a];
    made_.yaw[i] = model_->actuator_gear[6 * a + 5];
    made_.lag[i] = model_->actuator_dynprm[mjNDYN * a];
    made_.limit[i] = model_->actuator_ctrlrange[2 * a + 1];
  }
}

void MujocoVehicle::ScaleVehicle(const VehicleScaling& s) {
  mjModel* m = model_;
  m->body_mass[body_id_] = made_.mass * s.mass;
  for (int k = 0; k < 3; ++k) m->body_inertia[3 * body_id_ + k] = made_.inertia[k] * s.inertia[k];
  for (int i = 0; i < kNumRotors; ++i) {
    const int a = actuator_ids_[i];
    m->actuator_gainprm[mjNGAIN * a] = made_.gain[i] * s.thrust[i];
    m->actuator_gear[6 * a + 5] = made_.yaw[i] * s.yaw_moment[i];
    m->actuator_dynprm[mjNDYN * a] = made_.lag[i] * s.motor_lag[i];
    m->actuator_ctrlrange[2 * a + 1] = made_.limit[i] * s.rotor_limit[i];
  }
  mj_setConst(m, data_);
  ResetData();
}

void MujocoVehicle::ResetData() {
  mj_resetData(model_, data_);
  ++*resets_;  // every vehicle's warnings count from 0 again
  mj_forward(model_, data_);
}

void MujocoVehicle::SetCommands(const Vec4& thrust_commands) {
  for (int i = 0; i < kNumRotors; ++i) data_->ctrl[actuator_ids_[i]] = thrust_commands[i];
}

void MujocoVehicle::Step(const Vec4& thrust_commands) {
  SetCommands(thrust_commands);
  mj_step(model_, data_);
}

void MujocoVehicle::SetExternalWrench(const Vec3& force_W, const Vec3& torque_W) {
  double* applied = data_->xfrc_applied + 6 * body_id_;
  Eigen::Map<Vec3> force(applied);
  Eigen::Map<Vec3> torque(applied + 3);
  force = force_W;
  torque = torque_W;
}

Vec4 MujocoVehicle::RotorThrusts() const {
  Vec4 thrusts;
  for (int i = 0; i < kNumRotors; ++i) {
    thrusts[i] = data_->act[act_adr_[i]];
  }
  return thrusts;
}

void MujocoVehicle::SetRotorThrusts(const Vec4& thrusts) {
  for (int i = 0; i < kNumRotors; ++i) {
    data_->act[act_adr_[i]] = thrusts[i];
    data_->ctrl[actuator_ids_[i]] = thrusts[i];
  }
  mj_forward(model_, data_);
}

void MujocoVehicle::SetProducedThrusts(const Vec4& thrusts) {
  for (int i = 0; i < kNumRotors; ++i) data_->act[act_adr_[i]] = thrusts[i];
}

State MujocoVehicle::VehicleState() const {
  State state;
  const double* qpos = data_->qpos + qpos_adr_;
  const double* qvel = data_->qvel + qvel_adr_;
  state.p_W = Vec3(qpos[0], qpos[1], qpos[2]);
  state.q_WB = QuatFromWxyz(qpos + 3);
  state.v_W = Vec3(qvel[0], qvel[1], qvel[2]);
  state.w_B = Vec3(qvel[3], qvel[4], qvel[5]);
  return state;
}

void MujocoVehicle::SetVehicleState(const State& state) {
  double* qpos = data_->qpos + qpos_adr_;
  double* qvel = data_->qvel + qvel_adr_;
  Eigen::Map<Vec3> p_W(qpos);
  Eigen::Map<Vec3> v_W(qvel);
  Eigen::Map<Vec3> w_B(qvel + 3);
  p_W = state.p_W;
  QuatToWxyz(state.q_WB.normalized(), qpos + 3);
  v_W = state.v_W;
  w_B = state.w_B;
  mj_forward(model_, data_);
}

Vec3 MujocoVehicle::LinearAcceleration_W() const {
  return Eigen::Map<const Vec3>(data_->qacc + qvel_adr_);
}

Vec3 MujocoVehicle::AngularAcceleration_B() const {
  return Eigen::Map<const Vec3>(data_->qacc + qvel_adr_ + 3);
}

std::string MujocoVehicle::TakeNewWarnings() {
  std::string text;
  if (resets_seen_ != *resets_) {  // the data was reset (MuJoCo's counts with it) since the last
    resets_seen_ = *resets_;
    warnings_seen_.fill(0);
  }
  for (int i = 0; i < mjNWARNING; ++i) {
    const mjWarningStat& stat = data_->warning[i];
    if (stat.number <= warnings_seen_[i]) continue;
    warnings_seen_[i] = stat.number;
    if (!text.empty()) text += "; ";
    text += mju_warningText(i, stat.lastinfo);
  }
  return text;
}

bool MujocoVehicle::VehicleTouches() const {
  for (int i = 0; i < data_->ncon; ++i) {
    const mjContact& contact = data_->contact[i];
    if ((model_->geom_bodyid[contact.geom1] == body_id_) !=
        (model_->geom_bodyid[contact.geom2] == body_id_)) {
      return true;
    }
  }
  return false;
}

std::vector<VehicleContact> MujocoVehicle::VehicleContacts() const {
  std::vector<VehicleContact> contacts;
  for (int i = 0; i < data_->ncon; ++i) {
    const mjContact& contact = data_->contact[i];
    const bool first_is_vehicle = model_->geom_bodyid[contact.geom1] == body_id_;
    const bool second_is_vehicle = model_->geom_bodyid[contact.geom2] == body_id_;
    if (first_is_vehicle == second_is_vehicle) continue;
    const int other = first_is_vehicle ? contact.geom2 : contact.geom1;
    const char* geom = mj_id2name(model_, mjOBJ_GEOM, other);
    std::string name = geom != nullptr ? geom : "";
    // a body of its own is another vehicle ("cf2/quad_hull"): named by the vehicle's name
    if (model_->geom_bodyid[other] != 0) name = name.substr(0, name.find('/'));
    contacts.push_back({name, Vec3(contact.pos[0], contact.pos[1], contact.pos[2]), contact.dist});
  }
  return contacts;
}

}  // namespace aerobox
