// The viewer's HTML page (bench/tool/viewer_page.html, compiled in by CMake) with its data.
#pragma once

#include <string>

namespace softstep::tool {

// The page with `meta_json` (a JSON object) and `data_base64` (the recorded arrays) inline.
std::string viewer_page(const std::string& meta_json, const std::string& data_base64);

}  // namespace softstep::tool
