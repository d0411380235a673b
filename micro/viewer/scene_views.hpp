#pragma once
// Saving a camera as a named view in a scene file (the viewer's V key). The new entry is inserted
// as text before the closing brace of the file's "views" object, so everything else in the file
// (key order, spacing, the hand-written layout of scenes/*.json) stays byte for byte as it was.
#include <string>
#include <vector>

#include "oit/scene/scene.hpp"

namespace oitbench::viewer {

// The view names of a scene file's "views" object in the order the file lists them (SceneDesc's
// views come out of a sorted map). Throws oit::SceneError for text that is not a JSON object.
std::vector<std::string> view_names_in_file_order(const std::string& path, const std::string& text);

// `wanted` when no view has that name; else wanted-2, wanted-3, ...; an empty `wanted` gives the
// first free of view-1, view-2, ...
std::string unique_view_name(const std::vector<std::string>& taken, const std::string& wanted);

// One view as the scene format writes it: { "eye": [x, y, z], "target": ..., "up": ..., "fov": F, "order": "..." }.
std::string view_json(const oit::View& view);

// The file text with `view` added to its "views" object, indented like the entries already there.
std::string insert_view(const std::string& path, const std::string& text, const oit::View& view);

// Reads the scene file, names the view (unique_view_name with `wanted`), inserts it, checks that the
// result parses as a scene holding that view, and replaces the file (written beside it, then renamed).
// Returns the name it was saved under; throws oit::SceneError (or std::runtime_error for I/O).
std::string save_view_to_scene_file(const std::string& path, oit::View view, const std::string& wanted);

}  // namespace oitbench::viewer
