#pragma once
// The MPM step on the CPU: the driver of driver.hpp over the OpenMP
// backend (Simulation, the engine's own), and over the serial device
// backend (SerialDeviceSimulation: the CUDA backend's order of work on one
// CPU thread, for the tests of the code the GPU runs).
#include "runout/mpm/backend_openmp.hpp"
#include "runout/mpm/backend_serial.hpp"
#include "runout/mpm/driver.hpp"
#include "runout/scene/scene.hpp"

namespace runout {

extern template class Driver<OpenMpBackend>;
extern template class Driver<SerialDeviceBackend>;

// The driver with its particles on the host.
template <class Backend>
class HostSimulation : public Driver<Backend> {
 public:
  explicit HostSimulation(const Scene& scene);                 // seeds the bodies
  HostSimulation(const Scene& scene, Particles particles);      // given particles

  Particles& particles() { return this->backend().host_particles(); }
  const Particles& particles() const { return this->backend().host_particles(); }
  const Grid& grid() const { return this->backend().grid(); }
};

extern template class HostSimulation<OpenMpBackend>;
extern template class HostSimulation<SerialDeviceBackend>;

using Simulation = HostSimulation<OpenMpBackend>;
using SerialDeviceSimulation = HostSimulation<SerialDeviceBackend>;

}  // namespace runout
