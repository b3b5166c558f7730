// The images behind report.html (bench/report/): every render, path-tracer row and reference of a
// bench run, each written three ways under DIR/images/: STEM.exr (linear radiance, the data), STEM.png
// (tone mapped, for looking at and for thumbnails) and STEM.js, the radiance as half floats in base64
// that the page's viewer loads with a <script> tag. A page opened from disk may not read the pixels of a
// PNG or an EXR it fetched (file:// pages are cross-origin to everything, and fetch() is refused there),
// but it may run a script from its own folder: exposure and the per-pixel error map need the radiance.
#pragma once

#include <filesystem>
#include <string>

#include "core/image.h"

namespace bounce::app {

// `data` as RFC 4648 base64 (with padding).
std::string base64(const std::string& data);

// STEM.js: `bounceImage("images/STEM", width, height, "<base64 of width*height*3 IEEE half floats, little
// endian, row 0 at the top>");`. Values beyond the half range become +-inf, NaN stays NaN.
std::string imageScript(const std::string& id, const core::Image& image);

// Writes DIR/images/STEM.{exr,png,js}, each atomically; returns "images/STEM", the id records and the
// page use. STEM is made of the caller's words with anything but [A-Za-z0-9._-] replaced by '_'.
std::string writeReportImage(const std::filesystem::path& dir, const std::string& stem, const core::Image& image);

} // namespace bounce::app
