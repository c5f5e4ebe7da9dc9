// Data files the program ships (assets/), carried inside the binary: cmake/Assets.cmake writes
// their text into a generated source, so gblens needs no files beside it at run time.
#pragma once
#include <map>
#include <string>

namespace gb {

// The text of an asset by its path under assets/ ("layouts/gblens.json"), or null.
const std::string* assetText(const std::string& path);
// Every asset: path under assets/ -> text.
const std::map<std::string, std::string>& assets();

}  // namespace gb
