// Python keyword arguments into any parameter struct, through its Describe (common/schema.h):
// each value checked against its field's type and range, an unknown argument refused naming
// the nearest one. Messages name the caller and the argument: "aerobox/Hover-v0: argument
// 'episode_time' = -1 s: expected 0.01 to 3600".
#pragma once

#include <pybind11/pybind11.h>

#include <functional>
#include <string>

#include "common/schema.h"

namespace aerobox {

// Sets the fields of `params` that `kwargs` names; raises ValueError (a bad value) or TypeError
// (an unknown argument) naming `who` and the argument.
void ReadKwargs(const pybind11::dict& kwargs, const std::string& who,
                const std::function<void(Archive&)>& describe);

template <typename P>
void ParamsFromKwargs(const pybind11::dict& kwargs, const std::string& who, P* params) {
  ReadKwargs(kwargs, who, [params](Archive& a) { params->Describe(a); });
}

}  // namespace aerobox
