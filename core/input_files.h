/// Every file the command has read, for the output-folder rule (harness/run/out_folder.h):
/// `--out` may not equal, contain or replace any of them. The one image reader notes every
/// image it opens (frames, captures, masks, references, supplied outputs); the scene loaders
/// note the extra files a scene is built from (OBJ meshes, glTF files, buffers and textures;
/// also kept per scene in Scene::files_read). A command collects them with InputFilesRead()
/// just before it checks its output folder. Process-wide and thread-safe (scenes load in
/// parallel).
#pragma once
#include <string>
#include <vector>

namespace aalab {

/// Notes that `path` (as opened) was read as an input of this command.
void NoteInputFile(const std::string& path);

/// Every path noted so far, in the order first noted, without repeats.
std::vector<std::string> InputFilesRead();

/// What is at `path`, for messages where a regular file was expected: "does not exist",
/// "is a folder", "is a FIFO (named pipe)", "is a character device", "is a block device",
/// "is a socket", "cannot be examined: <why>"; "" for a regular file (symlinks followed).
std::string WhatIsAt(const std::string& path);

/// UserError "<what> '<path>' <WhatIsAt> (<expected>)" unless `path` is a regular file.
/// Checked with stat before any open(): opening a FIFO for reading blocks for ever.
void RequireRegularFile(const std::string& path, const std::string& what, const std::string& expected);

}  // namespace aalab
