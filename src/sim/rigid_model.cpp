// RigidModel::Of: what the rigid body needs, read from MuJoCo's compiled model of a scene, and
// every assumption the rigid body makes about it checked.
#include "sim/rigid_model.h"

#include <mujoco/mujoco.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "sim/simulation.h"
#include "vehicle/model_names.h"
#include "vehicle/quad_params.h"

namespace aerobox {
namespace {

[[noreturn]] void Refuse(const std::string& element, const std::string& why) {
  throw std::invalid_argument("backend \"rigid\": " + element + ": " + why +
                              " (the rigid body reproduces MuJoCo only without it)");
}

std::string NameOf(const mjModel* m, mjtObj type, int id) {
  const char* name = mj_id2name(m, type, id);
  return name != nullptr      ? name
         : type == mjOBJ_GEOM ? "geom " + std::to_string(id)
                              : "element " + std::to_string(id);
}

bool IsIdentity(const double* q) { return q[0] == 1 && q[1] == 0 && q[2] == 0 && q[3] == 0; }

void CheckOptions(const mjModel* m) {
  if (m->opt.integrator != mjINT_EULER) Refuse("option integrator", "not Euler");
  if (m->opt.density != 0 || m->opt.viscosity != 0) Refuse("option density/viscosity", "fluid");
  for (int i = 0; i < 3; ++i) {
    if (m->opt.wind[i] != 0) Refuse("option wind", "MuJoCo's own wind");
  }
  if (m->nv != 6) Refuse("the model", std::to_string(m->nv) + " degrees of freedom, not 6");
  for (int i = 0; i < m->nv; ++i) {
    if (m->dof_damping[i] != 0 || m->dof_armature[i] != 0 || m->dof_frictionloss[i] != 0) {
      Refuse("the vehicle's joint", "damping, armature or friction loss");
    }
  }
}

void ReadRotors(const mjModel* m, int body, RigidModel* r) {
  for (int i = 0; i < kNumRotors; ++i) {
    const std::string name = model_names::ThrustActuator(i);
    const int a = mj_name2id(m, mjOBJ_ACTUATOR, name.c_str());
    if (a < 0) Refuse(name, "missing");
    const int site = m->actuator_trnid[2 * a];
    if (m->actuator_trntype[a] != mjTRN_SITE || m->site_bodyid[site] != body ||
        !IsIdentity(m->site_quat + 4 * site)) {
      Refuse(name, "not on an unrotated site of the vehicle");
    }
    const double* gear = m->actuator_gear + 6 * a;
    if (gear[0] != 0 || gear[1] != 0 || gear[2] != 1 || gear[3] != 0 || gear[4] != 0) {
      Refuse(name, "a gear other than (0 0 1 0 0 k)");
    }
    if (m->actuator_dyntype[a] != mjDYN_FILTER || m->actuator_gaintype[a] != mjGAIN_FIXED ||
        m->actuator_biastype[a] != mjBIAS_NONE || m->actuator_forcelimited[a] ||
        !m->actuator_ctrllimited[a]) {
      Refuse(name, "not a filtered, fixed-gain, command-limited actuator");
    }
    r->rotor_B[static_cast<size_t>(i)] =
        Vec3(m->site_pos[3 * site], m->site_pos[3 * site + 1], m->site_pos[3 * site + 2]);
    r->gain[i] = m->actuator_gainprm[mjNGAIN * a];
    r->yaw_moment[i] = gear[5];
    r->lag[i] = m->actuator_dynprm[mjNDYN * a];
    r->command_min[i] = m->actuator_ctrlrange[2 * a];
    r->command_max[i] = m->actuator_ctrlrange[2 * a + 1];
  }
}

// The world's colliding geoms: a floor plane and boxes, unrotated.
void ReadWorld(const mjModel* m, int hull, RigidModel* r) {
  for (int g = 0; g < m->ngeom; ++g) {
    if (m->geom_bodyid[g] != 0) continue;
    const bool collides = (m->geom_contype[g] & m->geom_conaffinity[hull]) ||
                          (m->geom_contype[hull] & m->geom_conaffinity[g]);
    if (!collides) continue;
    const std::string name = NameOf(m, mjOBJ_GEOM, g);
    if (!IsIdentity(m->geom_quat + 4 * g)) Refuse(name, "a rotated geom");
    const Vec3 pos(m->geom_pos[3 * g], m->geom_pos[3 * g + 1], m->geom_pos[3 * g + 2]);
    if (m->geom_type[g] == mjGEOM_PLANE && !r->has_floor) {
      r->has_floor = true;
      r->floor_z = pos.z();
    } else if (m->geom_type[g] == mjGEOM_BOX) {
      const Vec3 half(m->geom_size[3 * g], m->geom_size[3 * g + 1], m->geom_size[3 * g + 2]);
      r->boxes.push_back({pos - half, pos + half});
      r->box_names.push_back(name);
    } else {
      Refuse(name, "a colliding geom other than one floor plane and boxes");
    }
    if (m->geom_margin[g] != 0) Refuse(name, "a contact margin");
  }
}

}  // namespace

RigidModel RigidModel::Of(const Simulation& sim) {
  const mjModel* m = sim.model();
  CheckOptions(m);
  RigidModel r;
  r.timestep = m->opt.timestep;
  r.gravity = Vec3(m->opt.gravity[0], m->opt.gravity[1], m->opt.gravity[2]);
  const int body = mj_name2id(m, mjOBJ_BODY, model_names::kBody);
  if (body < 0 || m->body_parentid[body] != 0) Refuse(model_names::kBody, "missing or not free");
  for (int k = 0; k < 3; ++k) {
    if (m->body_ipos[3 * body + k] != 0) Refuse(model_names::kBody, "a centre of mass off origin");
  }
  if (!IsIdentity(m->body_iquat + 4 * body)) Refuse(model_names::kBody, "rotated inertia axes");
  r.mass = m->body_mass[body];
  r.inertia =
      Vec3(m->body_inertia[3 * body], m->body_inertia[3 * body + 1], m->body_inertia[3 * body + 2]);
  const int joint = m->body_jntadr[body];
  const double* q0 = m->qpos0 + m->jnt_qposadr[joint];
  r.initial_p_W = Vec3(q0[0], q0[1], q0[2]);
  r.initial_q_WB = Quat(q0[3], q0[4], q0[5], q0[6]);
  ReadRotors(m, body, &r);
  const int hull = mj_name2id(m, mjOBJ_GEOM, model_names::kHullGeom);
  if (hull < 0 || m->geom_type[hull] != mjGEOM_BOX || m->geom_bodyid[hull] != body ||
      !IsIdentity(m->geom_quat + 4 * hull) || m->geom_pos[3 * hull] != 0 ||
      m->geom_pos[3 * hull + 1] != 0 || m->geom_pos[3 * hull + 2] != 0) {
    Refuse(model_names::kHullGeom, "not a box at the vehicle's origin");
  }
  r.hull_half =
      Vec3(m->geom_size[3 * hull], m->geom_size[3 * hull + 1], m->geom_size[3 * hull + 2]);
  for (int g = 0; g < m->ngeom; ++g) {
    const bool visual = m->geom_contype[g] == 0 && m->geom_conaffinity[g] == 0;
    if (m->geom_bodyid[g] == body && g != hull && !visual) {
      Refuse(NameOf(m, mjOBJ_GEOM, g), "a second colliding geom on the vehicle");
    }
  }
  ReadWorld(m, hull, &r);
  return r;
}

}  // namespace aerobox
