#pragma once
// A minimal SVG line chart: a few named series over shared axes, for arena-sim --plot.
#include <string>
#include <vector>

namespace arena::sim {

struct series {
    std::string label;
    std::vector<double> xs;
    std::vector<double> ys;
    bool dashed = false;
};

std::string render_svg(const std::string& title, const std::string& x_label, const std::string& y_label,
                       const std::vector<series>& lines);

}  // namespace arena::sim
