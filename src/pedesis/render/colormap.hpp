#pragma once
// The colours particles are painted with: a categorical palette for species, viridis for
// speeds (perceptually uniform, readable in grey and by most colour-blind viewers), and a
// cyclic map for polarity angles (the colours at 0 and 2 pi meet without a seam).
#include <cstddef>

namespace pedesis::render {

struct Rgb {
    double r = 0.0, g = 0.0, b = 0.0; // each in [0, 1]
};

// Tableau 10, repeated after ten species; none is white or close to it, so a particle
// always stands out from the background.
Rgb species_colour(std::size_t index);

// Viridis at `fraction` of the bar, clamped to [0, 1].
Rgb speed_colour(double fraction);

// A sinebow: smooth, 2 pi-periodic in `radians`, every hue at similar brightness.
Rgb angle_colour(double radians);

// Relative luminance, to choose dark or light marks on top of a colour.
double luminance(const Rgb& c);

} // namespace pedesis::render
