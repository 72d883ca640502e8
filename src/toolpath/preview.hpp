#pragma once
// A picture to glance at before printing: the scaffold seen from the front
// (X-Z) and from above (X-Y), model in grey, pillars, tips, feet and bridges
// in colour. Plain SVG, deterministic.
#include <string>

#include "layers/layer_stack.hpp"
#include "plan/scaffold.hpp"
#include "toolpath/support_paths.hpp"

namespace scaffold::toolpath {

std::string preview_svg(const layers::LayerStack& stack, const plan::Scaffold& scaffold, const SupportPaths& paths,
                        const Settings& settings);

}  // namespace scaffold::toolpath
