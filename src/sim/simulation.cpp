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

}  // namespace

Simulation Simulation::FromXml(const std::string& xml, const std::string& source) {
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
  return Simulation(std::move(model), source);
}

Simulation Simulation::FromFile(const std::string& path) {
  InstallMujocoMessageHandlers();
  char error[1024] = "";
  MjModelPtr model(mj_loadXML(path.c_str(), nullptr, error, sizeof(error)));
  if (!model) throw InputError({path, 0}, "MJCF", error);
  return Simulation(std::move(model), path);
}

Simulation::Simulation(MjModelPtr model, const std::string& source) : model_(std::move(model)) {
  data_.reset(mj_makeData(model_.get()));
  body_id_ = RequireId(model_.get(), mjOBJ_BODY, model_names::kBody, source);
  const int joint = model_->body_jntadr[body_id_];
  if (joint < 0 || model_->jnt_type[joint] != mjJNT_FREE) {
    throw InputError({source, 0}, model_names::kBody, "the vehicle body has no free joint");
  }
  qpos_adr_ = model_->jnt_qposadr[joint];
  qvel_adr_ = model_->jnt_dofadr[joint];
  for (int i = 0; i < kNumRotors; ++i) {
    actuator_ids_[i] =
        RequireId(model_.get(), mjOBJ_ACTUATOR, model_names::ThrustActuator(i), source);
    // MuJoCo 2.2 keeps activations only for actuators with dynamics, and those come last
    // in the actuator list, so actuator k owns act[k - (nu - na)]
    act_adr_[i] = actuator_ids_[i] - (model_->nu - model_->na);
    if (model_->actuator_dyntype[actuator_ids_[i]] != mjDYN_FILTER || act_adr_[i] < 0) {
      throw InputError({source, 0}, model_names::ThrustActuator(i),
                       "the rotor actuator has no motor-lag filter");
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
  mj_forward(model_.get(), data_.get());
}

void Simulation::ScaleVehicle(const VehicleScaling& s) {
  mjModel* m = model_.get();
  m->body_mass[body_id_] = made_.mass * s.mass;
  for (int k = 0; k < 3; ++k) m->body_inertia[3 * body_id_ + k] = made_.inertia[k] * s.inertia[k];
  for (int i = 0; i < kNumRotors; ++i) {
    const int a = actuator_ids_[i];
    m->actuator_gainprm[mjNGAIN * a] = made_.gain[i] * s.thrust[i];
    m->actuator_gear[6 * a + 5] = made_.yaw[i] * s.yaw_moment[i];
    m->actuator_dynprm[mjNDYN * a] = made_.lag[i] * s.motor_lag[i];
    m->actuator_ctrlrange[2 * a + 1] = made_.limit[i] * s.rotor_limit[i];
  }
  mj_setConst(m, data_.get());
  ResetData();
}

Simulation Simulation::Clone() const {
  return Simulation(MjModelPtr(mj_copyModel(nullptr, model_.get())), "a copy of the scene");
}

void Simulation::ResetData() {
  mj_resetData(model_.get(), data_.get());
  warnings_seen_.fill(0);
  mj_forward(model_.get(), data_.get());
}

void Simulation::Step(const Vec4& thrust_commands) {
  for (int i = 0; i < kNumRotors; ++i) data_->ctrl[actuator_ids_[i]] = thrust_commands[i];
  mj_step(model_.get(), data_.get());
}

void Simulation::SetExternalWrench(const Vec3& force_W, const Vec3& torque_W) {
  double* applied = data_->xfrc_applied + 6 * body_id_;
  Eigen::Map<Vec3> force(applied);
  Eigen::Map<Vec3> torque(applied + 3);
  force = force_W;
  torque = torque_W;
}

Vec4 Simulation::RotorThrusts() const {
  Vec4 thrusts;
  for (int i = 0; i < kNumRotors; ++i) {
    thrusts[i] = data_->act[act_adr_[i]];
  }
  return thrusts;
}

void Simulation::SetRotorThrusts(const Vec4& thrusts) {
  for (int i = 0; i < kNumRotors; ++i) {
    data_->act[act_adr_[i]] = thrusts[i];
    data_->ctrl[actuator_ids_[i]] = thrusts[i];
  }
  mj_forward(model_.get(), data_.get());
}

void Simulation::SetProducedThrusts(const Vec4& thrusts) {
  for (int i = 0; i < kNumRotors; ++i) data_->act[act_adr_[i]] = thrusts[i];
}

State Simulation::VehicleState() const {
  State state;
  const double* qpos = data_->qpos + qpos_adr_;
  const double* qvel = data_->qvel + qvel_adr_;
  state.p_W = Vec3(qpos[0], qpos[1], qpos[2]);
  state.q_WB = QuatFromWxyz(qpos + 3);
  state.v_W = Vec3(qvel[0], qvel[1], qvel[2]);
  state.w_B = Vec3(qvel[3], qvel[4], qvel[5]);
  return state;
}

void Simulation::SetVehicleState(const State& state) {
  double* qpos = data_->qpos + qpos_adr_;
  double* qvel = data_->qvel + qvel_adr_;
  Eigen::Map<Vec3> p_W(qpos);
  Eigen::Map<Vec3> v_W(qvel);
  Eigen::Map<Vec3> w_B(qvel + 3);
  p_W = state.p_W;
  QuatToWxyz(state.q_WB.normalized(), qpos + 3);
  v_W = state.v_W;
  w_B = state.w_B;
  mj_forward(model_.get(), data_.get());
}

Vec3 Simulation::LinearAcceleration_W() const {
  return Eigen::Map<const Vec3>(data_->qacc + qvel_adr_);
}

Vec3 Simulation::AngularAcceleration_B() const {
  return Eigen::Map<const Vec3>(data_->qacc + qvel_adr_ + 3);
}

std::string Simulation::TakeNewWarnings() {
  std::string text;
  for (int i = 0; i < mjNWARNING; ++i) {
    const mjWarningStat& stat = data_->warning[i];
    if (stat.number <= warnings_seen_[i]) continue;
    warnings_seen_[i] = stat.number;
    if (!text.empty()) text += "; ";
    text += mju_warningText(i, stat.lastinfo);
  }
  return text;
}

bool Simulation::VehicleTouches() const {
  for (int i = 0; i < data_->ncon; ++i) {
    const mjContact& contact = data_->contact[i];
    if ((model_->geom_bodyid[contact.geom1] == body_id_) !=
        (model_->geom_bodyid[contact.geom2] == body_id_)) {
      return true;
    }
  }
  return false;
}

std::vector<VehicleContact> Simulation::VehicleContacts() const {
  std::vector<VehicleContact> contacts;
  for (int i = 0; i < data_->ncon; ++i) {
    const mjContact& contact = data_->contact[i];
    const bool first_is_vehicle = model_->geom_bodyid[contact.geom1] == body_id_;
    const bool second_is_vehicle = model_->geom_bodyid[contact.geom2] == body_id_;
    if (first_is_vehicle == second_is_vehicle) continue;
    const int other = first_is_vehicle ? contact.geom2 : contact.geom1;
    const char* name = mj_id2name(model_.get(), mjOBJ_GEOM, other);
    contacts.push_back({name != nullptr ? name : "",
                        Vec3(contact.pos[0], contact.pos[1], contact.pos[2]), contact.dist});
  }
  return contacts;
}

}  // namespace aerobox
