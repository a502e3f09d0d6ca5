/// Which channels of a capture file an image scene reads (docs/own-frames.md "Channels and
/// layers"): colour, depth, ids and motion vectors chosen by channel name, with the common
/// renderers' layer names understood (Blender/Cycles multilayer EXR: ViewLayer.Combined.R,
/// ViewLayer.Depth.Z, ViewLayer.IndexOB.X, ViewLayer.Vector.X) and an explicit layer or channel
/// list for anything else. Pure functions over the names io's ListImageChannels gives.
#pragma once
#include <string>
#include <vector>

namespace aalab {

/// What a view's image field holds.
enum class ChannelRole {
  kColour,  ///< 3 channels: R, G, B (a 1-channel grey file: that channel, used as R = G = B)
  kDepth,   ///< 1 channel
  kIds,     ///< 1 to 3 channels (an id may be a colour)
  kMotion,  ///< 2 channels: x, y
};

/// "colour", "depth", "object ids", "motion vectors".
std::string RoleName(ChannelRole role);

/// The channels to read for `role` from a file with channels `have` (file order).
/// `layer` (may be empty): a layer prefix such as "ViewLayer.Combined" (its channels are
/// LAYER.R/G/B, LAYER.Z, LAYER.X/Y...). `channels` (may be empty): exact names, used as given.
/// Without either, the automatic rules (docs/own-frames.md) apply. A colour file with one
/// channel returns it once (the caller expands it). On failure returns an empty list and sets
/// `*why` to a message that lists the file's channels and says what to write instead.
std::vector<std::string> PickChannels(const std::vector<std::string>& have, ChannelRole role, const std::string& layer,
                                      const std::vector<std::string>& channels, std::string* why);

}  // namespace aalab
