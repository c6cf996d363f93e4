#pragma once
// One explicit MPM step, stage by stage, as per-particle and per-node
// functions. They take plain views and a scatter functor, hold no state and
// allocate nothing, so the driver (driver.hpp) runs them unchanged on every
// backend, a CUDA kernel included. This header includes them all, by concern:
//   step_config.hpp   StepConfig, the per-step gravity and FLIP share, the CFL speed
//   stencil.hpp       the GIMP stencils (lattice reduction) and node visits
//   geo_contact.hpp   boundary conditions and Geo-contact with the base
//   musl_stages.hpp   stages 1 to 6
//   stress_update.hpp stage 7
//   periodic.hpp      the periodic seam
//
// The step is MUSL (modified update-stress-last, Sulsky et al. 1995):
//   1. p2g:            m_i, p_i = sum N m v, f_i = sum -V sigma grad N,
//                      gap_i = min over the node's particles of their gap to the base
//   2. grid_update:    v0_i = p_i/m_i, v_i = v0_i + dt (f_i/m_i + g), Geo-contact with
//                      the rigid base where the material reaches it, boundary
//                      conditions
//   3. g2p:            FLIP, v_p += sum N (v_i - v0_i), with an optional PIC
//                      share at a physical rate; or APIC, v_p = sum N v_i
//                      and the affine velocity C_p; or a per-step blend
//   4. p2g_momentum:   p_i = sum N m (v_p + C_p (x_i - x_p))   (the MUSL remap)
//   5. remap_velocity: v_i = p_i/m_i and the mid-step vm_i = (v0_i + v_i)/2,
//                      contact kinematics, boundary conditions
//   6. velocity_gradient, displacement: L = sum v_i (x) grad N (its
//                      volumetric part averaged per cell against locking),
//                      step displacement dt sum N vm_i
//   7. stress_update:  volume, F, Jaumann stress; then move
// MUSL rather than USL because the stress is computed from the remapped
// velocity: at nodes with a tiny share of mass (free surface, a particle
// entering a cell) v0 + dt f/m is spurious, and USL turns it into stress.
// The price is a second scatter of momentum. Every stage evaluates the
// shape functions at the positions of the start of the step, so the
// particle moves only in the last stage.
#include "runout/mpm/geo_contact.hpp"
#include "runout/mpm/musl_stages.hpp"
#include "runout/mpm/periodic.hpp"
#include "runout/mpm/step_config.hpp"
#include "runout/mpm/stencil.hpp"
#include "runout/mpm/stress_update.hpp"
