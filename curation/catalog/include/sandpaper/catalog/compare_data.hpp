#pragma once
// What the compare page (assets/compare.html) shows of one entry, beside its page:
// entries/<name>.compare.js, a statement that adds the entry to window.sandpaperCompare. Loaded by
// <script src> as the index's data is (browsers refuse fetch() of file://), only for the entries
// a reader ticked.
#include <string>

#include "sandpaper/catalog/index_page.hpp"
#include "sandpaper/catalog/plot.hpp"

namespace sandpaper::catalog {

// entries/<name>.compare.js for `name`.
std::string compare_data_file(const std::string& name);

// The statement `(window.sandpaperCompare = window.sandpaperCompare || []).push(JSON.parse('...'));`
// with {"format": 1, "name", "describes", "family", "licence", "root", "roughness": number|null,
// "max_lateral_force_N", "period_m" (0: none), "kind", "terms", "sources": [kind words], "device",
// "thumbnail": file name beside it or null, "window_m": the thumbnail's square side (m),
// "scan": {"description", "speed_m_s", "s_mm": [...], "along_N": [...]}}. The scan's samples are
// those a line through them keeps within 0.1 % of the scan's length and of its force range
// (kept_points), s to 0.1 um and force to 4 significant digits: the same curve in a tenth of the bytes.
std::string compare_data_script(const IndexRow& row, const std::string& family_title, const std::string& device,
                                const std::string& terms, const ForceScan& scan, double window_m);

}  // namespace sandpaper::catalog
