#include "runout/mpm/simulation.hpp"

#include "runout/mpm/seeding.hpp"

namespace runout {

template <class Backend>
HostSimulation<Backend>::HostSimulation(const Scene& scene)
    : HostSimulation(scene, seed_particles(scene)) {}

template <class Backend>
HostSimulation<Backend>::HostSimulation(const Scene& scene, Particles particles)
    : Driver<Backend>(scene, std::move(particles)) {}

template class Driver<OpenMpBackend>;
template class Driver<SerialDeviceBackend>;
template class HostSimulation<OpenMpBackend>;
template class HostSimulation<SerialDeviceBackend>;

}  // namespace runout
