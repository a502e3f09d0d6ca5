// Channel choice for image scenes: colour, depth, ids and motion by name (image_channels.h).
#include "scenes/image_channels.h"

#include <algorithm>

namespace aalab {

namespace {

bool Has(const std::vector<std::string>& have, const std::string& name) {
  return std::find(have.begin(), have.end(), name) != have.end();
}

/// The layer of a channel name: everything before the last '.' ("" when there is none).
std::string LayerOf(const std::string& name) {
  const auto dot = name.rfind('.');
  return dot == std::string::npos ? "" : name.substr(0, dot);
}

/// The last part of a name ("ViewLayer.Depth.Z" → "Z", "ViewLayer.Depth" → "Depth").
std::string LastPart(const std::string& name) {
  const auto dot = name.rfind('.');
  return dot == std::string::npos ? name : name.substr(dot + 1);
}

/// Every distinct layer (in file order) that has all of `suffixes` as channels.
std::vector<std::string> LayersWith(const std::vector<std::string>& have, const std::vector<std::string>& suffixes) {
  std::vector<std::string> out;
  for (const auto& n : have) {
    const std::string layer = LayerOf(n);
    if (layer.empty() || std::find(out.begin(), out.end(), layer) != out.end()) continue;
    bool all = true;
    for (const auto& s : suffixes) all = all && Has(have, layer + "." + s);
    if (all) out.push_back(layer);
  }
  return out;
}

std::vector<std::string> Prefixed(const std::string& layer, const std::vector<std::string>& suffixes) {
  std::vector<std::string> out;
  for (const auto& s : suffixes) out.push_back(layer.empty() ? s : layer + "." + s);
  return out;
}

std::string Quoted(const std::vector<std::string>& names) {
  std::string s;
  for (size_t i = 0; i < names.size(); ++i) s += (i ? ", " : "") + ("\"" + names[i] + "\"");
  return s;
}

/// The channels directly under `layer` (LAYER.X, not LAYER.SUB.X).
std::vector<std::string> ChannelsOf(const std::vector<std::string>& have, const std::string& layer) {
  std::vector<std::string> out;
  for (const auto& n : have) {
    if (LayerOf(n) == layer) out.push_back(n);
  }
  return out;
}

std::string Advice(const std::vector<std::string>& have, ChannelRole role) {
  std::vector<std::string> layers;
  for (const auto& n : have) {
    const std::string l = LayerOf(n);
    if (!l.empty() && std::find(layers.begin(), layers.end(), l) != layers.end()) continue;
    if (!l.empty()) layers.push_back(l);
  }
  const char* example = role == ChannelRole::kColour  ? "[\"R\", \"G\", \"B\"]"
                        : role == ChannelRole::kDepth ? "[\"Z\"]"
                        : role == ChannelRole::kIds   ? "[\"ViewLayer.IndexOB.X\"]"
                                                      : "[\"ViewLayer.Vector.X\", \"ViewLayer.Vector.Y\"]";
  std::string s = "the file has the channels " + Quoted(have);
  if (!layers.empty()) s += " (layers " + Quoted(layers) + ")";
  s += "; name the " + RoleName(role) +
       " with {\"path\": ..., \"layer\": \"LAYER\"} or {\"path\": ..., \"channels\": " + example + "}";
  return s;
}

size_t MinCount(ChannelRole r) { return r == ChannelRole::kMotion ? 2 : 1; }
size_t MaxCount(ChannelRole r) {
  return r == ChannelRole::kColour || r == ChannelRole::kIds ? 3 : r == ChannelRole::kMotion ? 2 : 1;
}

std::vector<std::string> FromLayer(const std::vector<std::string>& have, ChannelRole role, const std::string& layer) {
  const std::vector<std::string> own = ChannelsOf(have, layer);
  auto all = [&](const std::vector<std::string>& s) {
    for (const auto& n : Prefixed(layer, s)) {
      if (!Has(have, n)) return false;
    }
    return true;
  };
  switch (role) {
    case ChannelRole::kColour:
      if (all({"R", "G", "B"})) return Prefixed(layer, {"R", "G", "B"});
      break;
    case ChannelRole::kDepth:
      if (all({"Z"})) return Prefixed(layer, {"Z"});
      if (own.size() == 1) return own;
      break;
    case ChannelRole::kIds:
      if (all({"X"})) return Prefixed(layer, {"X"});
      if (own.size() == 1) return own;
      if (all({"R", "G", "B"})) return Prefixed(layer, {"R", "G", "B"});
      break;
    case ChannelRole::kMotion:
      if (all({"X", "Y"})) return Prefixed(layer, {"X", "Y"});
      if (all({"R", "G"})) return Prefixed(layer, {"R", "G"});
      break;
  }
  return {};
}

/// The automatic rules, in order; empty when none applies (or the choice is ambiguous).
std::vector<std::string> Automatic(const std::vector<std::string>& have, ChannelRole role) {
  switch (role) {
    case ChannelRole::kColour: {
      if (Has(have, "R") && Has(have, "G") && Has(have, "B")) return {"R", "G", "B"};
      const std::vector<std::string> layers = LayersWith(have, {"R", "G", "B"});
      if (layers.size() == 1) return Prefixed(layers[0], {"R", "G", "B"});
      std::vector<std::string> combined;  // Blender/Cycles: ViewLayer.Combined
      for (const auto& l : layers) {
        if (LastPart(l) == "Combined") combined.push_back(l);
      }
      if (combined.size() == 1) return Prefixed(combined[0], {"R", "G", "B"});
      if (have.size() == 1) return have;  // grey
      if (Has(have, "Y") && (have.size() == 1 || (have.size() == 2 && Has(have, "A")))) return {"Y"};
      return {};
    }
    case ChannelRole::kDepth: {
      if (have.size() == 1) return have;
      if (Has(have, "Z")) return {"Z"};  // RGBA+Z
      std::vector<std::string> z;        // LAYER.Depth.Z (Blender), or one LAYER.Z
      for (const auto& n : have) {
        if (LastPart(n) == "Z" && LastPart(LayerOf(n)) == "Depth") z.push_back(n);
      }
      if (z.size() == 1) return z;
      z.clear();
      for (const auto& n : have) {
        if (LastPart(n) == "Z") z.push_back(n);
      }
      if (z.size() == 1) return z;
      return {};
    }
    case ChannelRole::kIds: {
      for (const char* pass : {"IndexOB", "IndexMA"}) {  // Blender: object index, then material index
        std::vector<std::string> x;
        for (const auto& n : have) {
          if (LastPart(n) == "X" && LastPart(LayerOf(n)) == pass) x.push_back(n);
        }
        if (x.size() == 1) return x;
        if (x.size() > 1) return {};
      }
      if (have.size() == 1) return have;
      if (Has(have, "R") && Has(have, "G") && Has(have, "B")) return {"R", "G", "B"};
      if (Has(have, "Y")) return {"Y"};
      return {};
    }
    case ChannelRole::kMotion: {
      std::vector<std::string> layers;  // Blender: LAYER.Vector.X/Y/Z/W
      for (const auto& l : LayersWith(have, {"X", "Y"})) {
        if (LastPart(l) == "Vector") layers.push_back(l);
      }
      if (layers.size() == 1) return Prefixed(layers[0], {"X", "Y"});
      if (Has(have, "R") && Has(have, "G")) return {"R", "G"};
      if (have.size() == 2) return have;
      return {};
    }
  }
  return {};
}

}  // namespace

std::string RoleName(ChannelRole role) {
  switch (role) {
    case ChannelRole::kColour: return "colour";
    case ChannelRole::kDepth: return "depth";
    case ChannelRole::kIds: return "object ids";
    case ChannelRole::kMotion: return "motion vectors";
  }
  return "";
}

std::vector<std::string> PickChannels(const std::vector<std::string>& have, ChannelRole role, const std::string& layer,
                                      const std::vector<std::string>& channels, std::string* why) {
  if (!channels.empty()) {
    if (channels.size() < MinCount(role) || channels.size() > MaxCount(role) ||
        (role == ChannelRole::kColour && channels.size() == 2)) {
      *why = RoleName(role) + " takes " +
             (MinCount(role) == MaxCount(role)
                  ? std::to_string(MinCount(role))
                  : std::to_string(MinCount(role)) + " to " + std::to_string(MaxCount(role))) +
             " channel(s), \"channels\" lists " + std::to_string(channels.size());
      if (role == ChannelRole::kColour)
        *why = "colour takes 3 channels (R, G, B) or 1 (grey), \"channels\" lists " + std::to_string(channels.size());
      return {};
    }
    for (const auto& c : channels) {
      if (!Has(have, c)) {
        *why = "there is no channel \"" + c + "\": " + Advice(have, role);
        return {};
      }
    }
    return channels;
  }
  if (!layer.empty()) {
    std::vector<std::string> out = FromLayer(have, role, layer);
    if (out.empty()) *why = "layer \"" + layer + "\" has no " + RoleName(role) + " channels: " + Advice(have, role);
    return out;
  }
  std::vector<std::string> out = Automatic(have, role);
  if (out.empty()) *why = "aalab cannot tell which channels hold the " + RoleName(role) + ": " + Advice(have, role);
  return out;
}

}  // namespace aalab
