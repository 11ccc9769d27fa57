// aerobox.envs' compiled core (_aerobox.EnvCore): see envs_binding.cpp.
#pragma once

#include <pybind11/pybind11.h>

namespace aerobox {

void BindEnvs(pybind11::module_& m);

}  // namespace aerobox
