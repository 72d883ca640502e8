#include "gcode/role.hpp"

#include <array>
#include <cctype>
#include <utility>

namespace scaffold::gcode {

namespace {

bool iequal(std::string_view a, std::string_view b) {
    if (a.size() != b.size()) return false;
    for (std::size_t i = 0; i < a.size(); ++i)
        if (std::tolower(static_cast<unsigned char>(a[i])) != std::tolower(static_cast<unsigned char>(b[i]))) return false;
    return true;
}

// Names used by PrusaSlicer/SuperSlicer, OrcaSlicer/Bambu, Cura and Slic3r.
constexpr std::array<std::pair<std::string_view, Role>, 44> kNames{{
    {"External perimeter", Role::ExternalPerimeter}, {"Perimeter", Role::Perimeter},
    {"Overhang perimeter", Role::OverhangPerimeter}, {"Internal infill", Role::InternalInfill},
    {"Solid infill", Role::SolidInfill}, {"Top solid infill", Role::TopSolidInfill},
    {"Bridge infill", Role::BridgeInfill}, {"Internal bridge infill", Role::BridgeInfill},
    {"Gap fill", Role::SolidInfill}, {"Skirt", Role::Skirt}, {"Skirt/Brim", Role::Skirt},
    {"Brim", Role::Skirt}, {"Support material", Role::Support},
    {"Support material interface", Role::SupportInterface}, {"Wipe tower", Role::WipeTower},
    {"Custom", Role::Custom}, {"Ironing", Role::TopSolidInfill},
    // OrcaSlicer / Bambu Studio
    {"Outer wall", Role::ExternalPerimeter}, {"Inner wall", Role::Perimeter},
    {"Overhang wall", Role::OverhangPerimeter}, {"Sparse infill", Role::InternalInfill},
    {"Internal solid infill", Role::SolidInfill}, {"Top surface", Role::TopSolidInfill},
    {"Bottom surface", Role::SolidInfill}, {"Bridge", Role::BridgeInfill},
    {"Support", Role::Support}, {"Support interface", Role::SupportInterface},
    {"Support transition", Role::Support}, {"Prime tower", Role::WipeTower},
    // Cura
    {"WALL-OUTER", Role::ExternalPerimeter}, {"WALL-INNER", Role::Perimeter},
    {"FILL", Role::InternalInfill}, {"SKIN", Role::SolidInfill}, {"SKIRT", Role::Skirt},
    {"SUPPORT", Role::Support}, {"SUPPORT-INTERFACE", Role::SupportInterface},
    {"PRIME-TOWER", Role::WipeTower}, {"PRIME_TOWER", Role::WipeTower},
    // Slic3r 1.x per-line comments
    {"perimeter (bridge)", Role::OverhangPerimeter}, {"infill (bridge)", Role::BridgeInfill},
    {"infill", Role::InternalInfill}, {"support material interface", Role::SupportInterface},
    {"move to first perimeter point", Role::Unknown}, {"skirt", Role::Skirt},
}};

// Simplify3D 3.x/4.x feature comments, and Kiri:Moto's (its walls are
// "shells"). A raft is support (Cura's is typed SUPPORT too); the ooze
// shield and prime pillar are printed for the nozzle.
constexpr std::array<std::pair<std::string_view, Role>, 16> kSimplify3D{{
    {"outer perimeter", Role::ExternalPerimeter}, {"inner perimeter", Role::Perimeter},
    {"solid layer", Role::SolidInfill}, {"infill", Role::InternalInfill}, {"gap fill", Role::SolidInfill},
    {"bridge", Role::BridgeInfill}, {"skirt", Role::Skirt}, {"support", Role::Support},
    {"dense support", Role::SupportInterface}, {"raft", Role::Support}, {"prime pillar", Role::WipeTower},
    {"ooze shield", Role::WipeTower}, {"shells", Role::Perimeter}, {"solid fill", Role::SolidInfill},
    {"sparse infill", Role::InternalInfill}, {"brim", Role::Skirt},
}};

// KISSlicer's path comments ("; 'Support Interface Path', 1.9 [feed mm/s]").
constexpr std::array<std::pair<std::string_view, Role>, 9> kKisslicer{{
    {"Perimeter Path", Role::ExternalPerimeter}, {"Loop Path", Role::Perimeter}, {"Solid Path", Role::SolidInfill},
    {"Sparse Infill Path", Role::InternalInfill}, {"Stacked Sparse Infill Path", Role::InternalInfill},
    {"Support (may Stack) Path", Role::Support}, {"Support Interface Path", Role::SupportInterface},
    {"Raft Path", Role::Support}, {"Skirt Path", Role::Skirt},
}};

}  // namespace

bool kisslicer_role(std::string_view comment, Role& role) {
    if (comment.size() < 3 || comment.front() != '\'') return false;
    const std::size_t end = comment.find('\'', 1);
    if (end == std::string_view::npos) return false;
    const std::string_view name = comment.substr(1, end - 1);
    if (name.size() < 5 || name.substr(name.size() - 5) != " Path") return false;
    role = Role::Unknown;
    for (const auto& [n, r] : kKisslicer)
        if (n == name) role = r;
    return true;
}

bool simplify3d_role(std::string_view name, Role& role) {
    while (!name.empty() && (name.back() == ' ' || name.back() == '\r')) name.remove_suffix(1);
    // Simplify3D 4.1 and 5 write "; feature outer perimeter".
    if (name.size() > 8 && iequal(name.substr(0, 8), "feature ")) name.remove_prefix(8);
    for (const auto& [n, r] : kSimplify3D)
        if (iequal(n, name)) {
            role = r;
            return true;
        }
    return false;
}

Role role_from_name(std::string_view name) {
    while (!name.empty() && (name.back() == ' ' || name.back() == '\r')) name.remove_suffix(1);
    for (const auto& [n, r] : kNames)
        if (iequal(n, name)) return r;
    return Role::Unknown;
}

std::string_view role_name(Role role) {
    switch (role) {
        case Role::ExternalPerimeter: return "External perimeter";
        case Role::Perimeter: return "Perimeter";
        case Role::OverhangPerimeter: return "Overhang perimeter";
        case Role::InternalInfill: return "Internal infill";
        case Role::SolidInfill: return "Solid infill";
        case Role::TopSolidInfill: return "Top solid infill";
        case Role::BridgeInfill: return "Bridge infill";
        case Role::Skirt: return "Skirt/Brim";
        case Role::Support: return "Support material";
        case Role::SupportInterface: return "Support material interface";
        case Role::WipeTower: return "Wipe tower";
        case Role::Custom: return "Custom";
        case Role::Unknown: break;
    }
    return "Unknown";
}

}  // namespace scaffold::gcode
