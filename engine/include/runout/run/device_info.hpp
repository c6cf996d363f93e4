#pragma once
#include <string>
#include <vector>

namespace runout {

// The CUDA devices this build can use, one line each ("0: NVIDIA H200, 139
// GiB, sm_90"). Empty with the reason in why_none when there are none (no
// CUDA in this build, no driver, no device).
std::vector<std::string> cuda_devices(std::string& why_none);

}  // namespace runout
