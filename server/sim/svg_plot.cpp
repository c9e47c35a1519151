#include "server/sim/svg_plot.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace arena::sim {

namespace {

constexpr double width = 800, height = 500, left = 80, right = 200, top = 50, bottom = 60;
const char* colours[] = {"#d62728", "#1f77b4", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b"};

std::string num(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.4g", v);
    return buf;
}

std::string escape(const std::string& s) {
    std::string out;
    for (char c : s) {
        if (c == '<')
            out += "&lt;";
        else if (c == '>')
            out += "&gt;";
        else if (c == '&')
            out += "&amp;";
        else
            out += c;
    }
    return out;
}

}  // namespace

std::string render_svg(const std::string& title, const std::string& x_label, const std::string& y_label,
                       const std::vector<series>& lines) {
    double x0 = std::numeric_limits<double>::max(), x1 = -x0, y0 = x0, y1 = -x0;
    for (const series& s : lines) {
        for (double x : s.xs) x0 = std::min(x0, x), x1 = std::max(x1, x);
        for (double y : s.ys) y0 = std::min(y0, y), y1 = std::max(y1, y);
    }
    if (x0 > x1) x0 = 0, x1 = 1, y0 = 0, y1 = 1;
    if (x1 == x0) x1 = x0 + 1;
    if (y1 == y0) y1 = y0 + 1;
    const double pw = width - left - right, ph = height - top - bottom;
    auto px = [&](double x) {
        return left + (x - x0) / (x1 - x0) * pw;
    };
    auto py = [&](double y) {
        return top + ph - (y - y0) / (y1 - y0) * ph;
    };

    std::string svg = "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + num(width) + "\" height=\"" + num(height) +
                      "\" font-family=\"sans-serif\" font-size=\"13\">\n";
    svg += "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
    svg += "<text x=\"" + num(width / 2) + "\" y=\"25\" text-anchor=\"middle\" font-size=\"16\">" + escape(title) +
           "</text>\n";
    svg += "<rect x=\"" + num(left) + "\" y=\"" + num(top) + "\" width=\"" + num(pw) + "\" height=\"" + num(ph) +
           "\" fill=\"none\" stroke=\"black\"/>\n";
    for (int i = 0; i <= 5; ++i) {
        const double fx = x0 + (x1 - x0) * i / 5, fy = y0 + (y1 - y0) * i / 5;
        svg += "<text x=\"" + num(px(fx)) + "\" y=\"" + num(top + ph + 18) + "\" text-anchor=\"middle\">" + num(fx) +
               "</text>\n";
        svg += "<text x=\"" + num(left - 6) + "\" y=\"" + num(py(fy) + 4) + "\" text-anchor=\"end\">" + num(fy) +
               "</text>\n";
        svg += "<line x1=\"" + num(left) + "\" x2=\"" + num(left + pw) + "\" y1=\"" + num(py(fy)) + "\" y2=\"" +
               num(py(fy)) + "\" stroke=\"#ddd\"/>\n";
    }
    svg += "<text x=\"" + num(left + pw / 2) + "\" y=\"" + num(height - 15) + "\" text-anchor=\"middle\">" +
           escape(x_label) + "</text>\n";
    svg += "<text transform=\"translate(20," + num(top + ph / 2) + ") rotate(-90)\" text-anchor=\"middle\">" +
           escape(y_label) + "</text>\n";
    for (size_t i = 0; i < lines.size(); ++i) {
        const series& s = lines[i];
        const char* colour = colours[i % (sizeof colours / sizeof *colours)];
        std::string points;
        for (size_t k = 0; k < s.xs.size() && k < s.ys.size(); ++k)
            points += num(px(s.xs[k])) + "," + num(py(s.ys[k])) + " ";
        svg += "<polyline fill=\"none\" stroke=\"" + std::string(colour) + "\" stroke-width=\"2\"" +
               (s.dashed ? " stroke-dasharray=\"6,4\"" : "") + " points=\"" + points + "\"/>\n";
        const double ly = top + 20 + 22 * static_cast<double>(i);
        svg += "<line x1=\"" + num(width - right + 15) + "\" x2=\"" + num(width - right + 45) + "\" y1=\"" + num(ly) +
               "\" y2=\"" + num(ly) + "\" stroke=\"" + colour + "\" stroke-width=\"2\"" +
               (s.dashed ? " stroke-dasharray=\"6,4\"" : "") + "/>\n";
        svg += "<text x=\"" + num(width - right + 52) + "\" y=\"" + num(ly + 4) + "\">" + escape(s.label) + "</text>\n";
    }
    svg += "</svg>\n";
    return svg;
}

}  // namespace arena::sim
