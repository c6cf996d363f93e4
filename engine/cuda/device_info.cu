#include <cuda_runtime.h>

#include <cstdio>

#include "runout/run/device_info.hpp"

namespace runout {

std::vector<std::string> cuda_devices(std::string& why_none) {
  int count = 0;
  const cudaError_t err = cudaGetDeviceCount(&count);
  if (err != cudaSuccess) {
    why_none = std::string("no usable CUDA device: ") + cudaGetErrorString(err);
    return {};
  }
  if (count == 0) {
    why_none = "no CUDA device found";
    return {};
  }
  std::vector<std::string> out;
  for (int d = 0; d < count; ++d) {
    cudaDeviceProp prop;
    cudaGetDeviceProperties(&prop, d);
    char line[256];
    std::snprintf(line, sizeof line, "%d: %s, %.0f GiB, sm_%d%d, %d SMs", d, prop.name,
                  prop.totalGlobalMem / 1073741824.0, prop.major, prop.minor,
                  prop.multiProcessorCount);
    out.emplace_back(line);
  }
  return out;
}

}  // namespace runout
