#pragma once
// Plain enums shared by the scene (host) and the stage functions (host and
// device), kept apart from scene.hpp so device code needs no std::string.

namespace runout {

enum class ShapeKind { Gimp, Linear };
// A GIMP particle's domain: its initial square kept (uGIMP), or a rectangle
// that follows the particle's deformation (stencil.hpp, domain_half_widths).
enum class DomainKind { Deforming, Fixed };
// Grid-to-particle velocity transfer: FLIP with a PIC share that damps at a
// rate set in physical time, APIC (affine particle-in-cell, Jiang et al.
// 2015), or a per-step blend of PIC and FLIP.
enum class TransferKind { Flip, Apic, PicFlip, Xpic };
// Periodic: left and right together, the domain repeating along x.
enum class BoundaryKind { Free, Slip, Fixed, Periodic };
enum class MaterialModel { Elastic, Tresca };
// How the softened strength and the rate factor combine (SCENES.md):
// additive su0 S + su0 R, multiplicative su0 S (1 + R).
enum class StrengthForm { Additive, Multiplicative };
// The slide-base interface of Geo-contact: no-slip, a limiting shear
// stress tau (frictional, as in SCENES.md) or Coulomb friction mu.
enum class InterfaceKind { NoSlip, Frictional, Coulomb };
enum class BaseKind { None, Planar, Polyline };
// The method a scene runs with: the material point method or the
// depth-averaged model (docs/dam.md), and the latter's basal shear strain
// rate estimate.
enum class Method { Mpm, Dam };
enum class ShearRateEstimate { Linear, Plug, Band };

}  // namespace runout
