#pragma once
// Plain enums shared by the scene (host) and the stage functions (host and
// device), kept apart from scene.hpp so device code needs no std::string.

namespace runout {

enum class ShapeKind { Gimp, Linear };
enum class BoundaryKind { Free, Slip, Fixed };
enum class MaterialModel { Elastic };

}  // namespace runout
