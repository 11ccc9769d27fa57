// Ipopt's application return status in words, for the solves of this library (its header
// stays out of ours: the status travels as Ipopt's integer code).
#pragma once

#include <string>

namespace aerobox {

std::string DescribeIpoptStatus(int code);

}  // namespace aerobox
