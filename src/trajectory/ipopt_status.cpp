#include "trajectory/ipopt_status.h"

#include <IpReturnCodes.hpp>

namespace aerobox {

std::string DescribeIpoptStatus(int code) {
  const auto status = static_cast<Ipopt::ApplicationReturnStatus>(code);
  switch (status) {
    case Ipopt::Solve_Succeeded:
      return "solved";
    case Ipopt::Solved_To_Acceptable_Level:
      return "solved to acceptable level";
    case Ipopt::Infeasible_Problem_Detected:
      return "infeasible problem detected";
    case Ipopt::Search_Direction_Becomes_Too_Small:
      return "search direction becomes too small";
    case Ipopt::Diverging_Iterates:
      return "diverging iterates";
    case Ipopt::User_Requested_Stop:
      return "user requested stop";
    case Ipopt::Feasible_Point_Found:
      return "feasible point found";
    case Ipopt::Maximum_Iterations_Exceeded:
      return "maximum iterations exceeded";
    case Ipopt::Restoration_Failed:
      return "restoration failed";
    case Ipopt::Error_In_Step_Computation:
      return "error in step computation";
    case Ipopt::Maximum_CpuTime_Exceeded:
      return "maximum CPU time exceeded";
    case Ipopt::Not_Enough_Degrees_Of_Freedom:
      return "not enough degrees of freedom";
    case Ipopt::Invalid_Problem_Definition:
      return "invalid problem definition";
    case Ipopt::Invalid_Option:
      return "invalid option";
    case Ipopt::Invalid_Number_Detected:
      return "invalid number detected";
    case Ipopt::Unrecoverable_Exception:
      return "unrecoverable exception";
    case Ipopt::NonIpopt_Exception_Thrown:
      return "non-Ipopt exception thrown";
    case Ipopt::Insufficient_Memory:
      return "insufficient memory";
    case Ipopt::Internal_Error:
      return "internal error";
  }
  return "unknown Ipopt status " + std::to_string(static_cast<int>(status));
}

}  // namespace aerobox
