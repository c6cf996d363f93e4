#include "runout/run/device_info.hpp"

namespace runout {

std::vector<std::string> cuda_devices(std::string& why_none) {
  why_none = "this build has no CUDA (nvcc was not found at configure time)";
  return {};
}

}  // namespace runout
