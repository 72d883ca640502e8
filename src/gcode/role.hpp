#pragma once
// Extrusion roles, normalised over the slicer dialects (;TYPE: names,
// Slic3r per-line comments, Cura's upper-case types).
#include <cstdint>
#include <string_view>

namespace scaffold::gcode {

enum class Role : std::uint8_t {
    Unknown,
    ExternalPerimeter,
    Perimeter,
    OverhangPerimeter,
    InternalInfill,
    SolidInfill,
    TopSolidInfill,
    BridgeInfill,
    Skirt,
    Support,
    SupportInterface,
    WipeTower,
    Custom,
};

// Role named by a ;TYPE: value or a Slic3r per-line comment; Unknown if none.
Role role_from_name(std::string_view name);
// Simplify3D names each feature in a comment line of its own ("; outer
// perimeter", "; support"; from 4.1 on "; feature support", as Kiri:Moto
// does too); false when `name` is none of them.
bool simplify3d_role(std::string_view name, Role& role);
// KISSlicer names each path in a comment ("'Support Interface Path', ...");
// false when `comment` is no such name, else the role (Unknown for the
// paths it has no role for: travel, destring, ...).
bool kisslicer_role(std::string_view comment, Role& role);
std::string_view role_name(Role role);
inline bool is_support(Role r) { return r == Role::Support || r == Role::SupportInterface; }
// Slicer-marked bridges: printed over air on purpose, held at both ends.
inline bool is_bridge(Role r) { return r == Role::BridgeInfill || r == Role::OverhangPerimeter; }

}  // namespace scaffold::gcode
