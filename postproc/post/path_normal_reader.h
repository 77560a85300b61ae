// The normals of a program posted without a model (issue 39): the path
// read once ahead of the post job, section by section, and each sample's
// normal estimated from the toolpath itself (pipeline/path_normals.h).
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "machines/profile.h"
#include "postproc/gcode/dialect.h"
#include "postproc/pipeline/path_normals.h"
#include "postproc/post/path_reader.h"
#include "postproc/post/post_job.h"
#include "postproc/tools/tool_table.h"

namespace vcpost::post {

// Without a model: the normal at every sample of the posted sections, in
// path order, from the toolpath itself (path_normals.h). The program is
// read once before the job for it: a sample's normal needs the pass after
// it too. Section by section (each tool's path lies on its own offset
// surface), neighbours within the section tool's diameter. Found at the
// moves' ends, the points the CAM system put on the surface; a sample
// inside a move (a long one, split at the spacing) takes the normal
// between those of its move's ends, as far along as it lies. With the
// bounds of the samples' programmed points.
PathNormalsAhead normals_from_path(std::string_view text, const std::string& file_name,
                                   ProgramKind kind, const gcode::Dialect& dialect,
                                   const machines::MachineProfile& profile,
                                   const PostSettings& settings, const tools::ToolChoices& choices);

}  // namespace vcpost::post
