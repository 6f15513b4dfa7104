// The record of which campaign a folder holds (DIR/campaign_identity.txt), so that a resume with an
// edited campaign file, or another campaign's file, into a folder is refused instead of labelling
// the folder's results with the new file's values. No MPI here.
#pragma once

#include <string>

#include "solver/driver/campaign_file.hpp"

namespace raceway::driver {

/// The campaign's identity as canonical text, one `label = value` per line: everything its results
/// and their labels depend on: its name, sweep, axes (column name and key), the base scene's text
/// line by line, and per scene every override and the settling time. Not the campaign file's path,
/// layout or comments, nor the metrics asked for (the table is drawn again from the same outputs),
/// nor the predicted costs (a later build may predict otherwise).
std::string campaign_identity(const Campaign& campaign);

/// The identity file of a campaign folder.
std::string identity_path(const std::string& dir);

/// Before a campaign touches DIR: when DIR holds an identity that is not `campaign`'s, throws
/// scene::SceneError naming the campaign file, the line and key of the first difference and the
/// differences (the folder's value and this file's); when DIR holds scene outputs but no identity,
/// throws too (they cannot be told apart). Touches nothing.
void check_identity(const Campaign& campaign, const std::string& dir);

/// Writes DIR/campaign_identity.txt (through a file of its own, renamed: array tasks write it at
/// once) when it is not there.
void record_identity(const Campaign& campaign, const std::string& dir);

}  // namespace raceway::driver
