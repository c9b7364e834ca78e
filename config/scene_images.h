// SPDX-License-Identifier: Apache-2.0
// SceneImages: the pixels of one scene's image annotations, each file decoded once however many annotations name it,
// and the sum of what they show bounded (kMaxSceneImageBytes) before anything past it is decoded. Private to config/.
#pragma once

#include <map>
#include <memory>
#include <string>

#include "config/toml_reader.h"
#include "overlay/shapes/annotation.h"

namespace overlayd {

class SceneImages
{
public:
    // The premultiplied RGBA pixels of the file at `path` for one more annotation, or nullptr after a problem at
    // the table's `path` key: a file that cannot be read or decoded, an image over kMaxImageSide, or one whose
    // pixels would take the scene's images past kMaxSceneImageBytes (judged from the header, before decoding); after
    // that one, nullptr without a problem (the images after it are not read).
    std::shared_ptr<const ImagePixels> load(TableReader &table, const std::string &path);

    // An annotation was refused for the total: the images after it are not read.
    bool full() const { return full_; }

private:
    bool withinTotal(TableReader &table, const std::string &path, unsigned width, unsigned height);

    std::map<std::string, std::shared_ptr<const ImagePixels>> decoded_;
    size_t totalBytes_ = 0; // what the annotations so far show: a file named twice counts twice (each is drawn)
    bool full_ = false;
};

} // namespace overlayd
