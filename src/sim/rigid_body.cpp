#include "sim/rigid_body.h"

#include <stdexcept>

namespace aerobox {

RigidBody::RigidBody(RigidModel model)
    : own_(std::make_unique<RigidBatch>(std::move(model), 1)), batch_(own_.get()), i_(0) {}

RigidBody::RigidBody(RigidBatch* batch, int index) : batch_(batch), i_(index) {
  if (batch == nullptr || index < 0 || index >= batch->size()) {
    throw std::out_of_range("RigidBody: no world " + std::to_string(index) + " in the batch");
  }
}

void RigidBody::Step(const Vec4& thrust_commands) {
  batch_->SetCommands(i_, thrust_commands);
  batch_->Step(i_, i_ + 1);
}

}  // namespace aerobox
