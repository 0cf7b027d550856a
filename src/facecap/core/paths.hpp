#pragma once
// Where facecap looks for the face model, the test footage and its cache.
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

namespace facecap {

// FACECAP_MODEL_DIR, else ../shared/models/ict-facekit beside the source tree,
// else the same path relative to the working folder.
std::filesystem::path default_model_dir();
// FACECAP_DATA_DIR, else ../shared/data beside the source tree (or the working folder).
std::filesystem::path default_data_dir();
// FACECAP_CACHE_DIR, else $XDG_CACHE_HOME/facecap, else ~/.cache/facecap.
std::filesystem::path cache_dir();
// The file under default_data_dir(), or nullopt when it is absent.
std::optional<std::filesystem::path> data_file(const std::string& name);
// True when running under CI (CI=true): absent model or data is then an error.
bool running_under_ci();
// The digits of a file name `<prefix><digits><suffix>` (one digit or more,
// nothing else between), or nullopt: how facecap recognises the numbered
// outputs of an earlier run (`animation_shot2.glb`, `face_3`).
std::optional<std::string_view> numbered_name_digits(std::string_view name, std::string_view prefix,
                                                     std::string_view suffix);

}  // namespace facecap
