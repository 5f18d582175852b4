#pragma once
// Picture files of a run: one frame's picture, or a numbered sequence of them (a movie's frames).
#include <array>
#include <string>
#include <vector>

#include "core/file_roles.hpp"
#include "render/canvas.hpp"
#include "render/run_picture.hpp"

namespace frac::render {

// picture-%04d.png with number 7 -> picture-0007.png. The pattern must hold one %d (with an optional
// zero-padded width) and no other % but %%: UsageError naming --output otherwise.
std::string numbered_name(const std::string& pattern, long long number);

// Writes frame `frame` of `picture` to `path`; returns the picture's size in pixels.
std::array<int, 2> write_frame_picture(const RunPicture& picture, long long frame, const CanvasSize& size,
                                       ImageFormat format, const std::string& path, const std::string& provenance);

// Writes the pictures of `frames` to numbered_name(pattern, 0), numbered_name(pattern, 1), ..., each name
// checked against the tool's `inputs` (check_file_roles) before it is written.
void write_picture_sequence(const RunPicture& picture, const std::vector<long long>& frames, const CanvasSize& size,
                            ImageFormat format, const std::string& pattern, const std::string& provenance,
                            const std::vector<FileRole>& inputs);

}  // namespace frac::render
