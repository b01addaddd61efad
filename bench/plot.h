#pragma once
// The bench's speed-against-error scatter plot, drawn with OpenImageIO (bench/draw.h).
#include "bench/draw.h"

#include <string>
#include <vector>

namespace deepgi::bench {

// One series of points in a speed-against-error plot.
struct PlotSeries {
    std::string name;
    draw::Colour color;
    std::vector<double> x, y;
    std::vector<std::string> labels;  // drawn next to the points of the Pareto front
};

// Scatter plot, x and y both minimised; each series' Pareto front is joined by a line and its points boxed and
// labelled. Axes from 0 to a rounded maximum (1, 2, 2.5, 5 x a power of ten), five ticks each.
OIIO::ImageBuf speedErrorPlot(const std::vector<PlotSeries>& series, const std::string& title, const std::string& xLabel,
                              const std::string& yLabel, int width = 900, int height = 600);

// The rounded axis maximum and tick step for data up to v (exposed for the tests).
void niceAxis(double v, double& max, double& step);

}  // namespace deepgi::bench
