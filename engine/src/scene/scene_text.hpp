#pragma once
// What the scene parser and the scene writer must agree on, kept in one
// place so a resolved scene always reads back as the Scene it came from:
// the spelling of every enumerated value, number formatting, and how a
// slope angle becomes a gravity vector.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>

#include <Eigen/Core>

#include "runout/scene/scene.hpp"

namespace runout::scene_text {

template <class Value>
struct Named {
  std::string_view name;
  Value value;
};

inline constexpr Named<ShapeKind> kShapeNames[] = {
    {"gimp", ShapeKind::Gimp}, {"linear", ShapeKind::Linear}};
inline constexpr Named<DomainKind> kDomainNames[] = {
    {"deforming", DomainKind::Deforming}, {"fixed", DomainKind::Fixed}};
inline constexpr Named<TransferKind> kTransferNames[] = {
    {"flip", TransferKind::Flip}, {"apic", TransferKind::Apic}, {"pic_flip", TransferKind::PicFlip}, {"xpic", TransferKind::Xpic}};
inline constexpr Named<BoundaryKind> kBoundaryNames[] = {
    {"free", BoundaryKind::Free},
    {"slip", BoundaryKind::Slip},
    {"fixed", BoundaryKind::Fixed},
    {"periodic", BoundaryKind::Periodic}};
inline constexpr Named<MaterialModel> kModelNames[] = {
    {"elastic", MaterialModel::Elastic}, {"tresca", MaterialModel::Tresca}};
inline constexpr Named<StrengthForm> kStrengthFormNames[] = {
    {"additive", StrengthForm::Additive},
    {"multiplicative", StrengthForm::Multiplicative}};
// BaseKind::None has no name: it is the absence of a [base] table.
inline constexpr Named<BaseKind> kBaseNames[] = {
    {"planar", BaseKind::Planar}, {"polyline", BaseKind::Polyline}};
inline constexpr Named<InterfaceKind> kInterfaceNames[] = {
    {"no_slip", InterfaceKind::NoSlip},
    {"frictional", InterfaceKind::Frictional},
    {"coulomb", InterfaceKind::Coulomb}};

inline constexpr Named<Method> kMethodNames[] = {{"mpm", Method::Mpm}, {"dam", Method::Dam}};
inline constexpr Named<ShearRateEstimate> kShearRateNames[] = {
    {"linear", ShearRateEstimate::Linear},
    {"plug", ShearRateEstimate::Plug},
    {"band", ShearRateEstimate::Band}};
inline constexpr Named<EarthPressure> kEarthPressureNames[] = {
    {"rankine", EarthPressure::Rankine}, {"hydrostatic", EarthPressure::Hydrostatic}};

template <class Value, std::size_t N>
std::string_view name_of(const Named<Value> (&names)[N], Value value) {
  for (const auto& entry : names)
    if (entry.value == value) return entry.name;
  return "?";  // unreachable while every enumerator has a name above
}

// The shortest decimal text that reads back as exactly the same double:
// resolved scenes round-trip, yet say 0.1 rather than 0.10000000000000001.
inline std::string format_number(double value) {
  char shortest[32];
  int digits = 1;
  for (; digits < 17; ++digits) {
    std::snprintf(shortest, sizeof shortest, "%.*g", digits, value);
    if (std::strtod(shortest, nullptr) == value) break;
  }
  if (digits == 17) std::snprintf(shortest, sizeof shortest, "%.17g", value);
  // %g turns to an exponent once the integer part has more digits than it
  // was asked for (90 -> "9e+01"); write such numbers out in full.
  if (!std::isfinite(value) || std::abs(value) < 1.0) return shortest;
  const int integer_digits = static_cast<int>(std::floor(std::log10(std::abs(value)))) + 1;
  if (integer_digits <= digits || integer_digits > 17) return shortest;
  char full[32];
  std::snprintf(full, sizeof full, "%.*g", integer_digits, value);
  return std::strtod(full, nullptr) == value ? full : shortest;
}

// The run is in the slope frame (x down the base), so gravity tilts by the
// slope angle.
inline Eigen::Vector2d slope_gravity(double magnitude, double angle_deg) {
  const double angle = angle_deg * 3.14159265358979323846 / 180.0;
  return magnitude * Eigen::Vector2d(std::sin(angle), -std::cos(angle));
}

}  // namespace runout::scene_text
