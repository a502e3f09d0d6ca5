// The bibliography of aalab's methods and metrics (reports/export_bibliography.h). Each entry
// is the source a method or metric file's doc block names; the registries refer to it by key.
#include "reports/export_bibliography.h"

#include <algorithm>

#include "build_info.h"
#include "core/error.h"

namespace aalab {

namespace {

struct Bib {
  const char* key;
  const char* entry;
};

// Checked against the documents in ../shared/seeds and the doc blocks of the method and
// metric files; pdfLaTeX-safe (accents as TeX macros, no CJK).
const Bib kBibliography[] = {
    {"lottes2009fxaa", R"(@techreport{lottes2009fxaa,
  author      = {Timothy Lottes},
  title       = {{FXAA}},
  institution = {NVIDIA Corporation},
  type        = {White paper},
  year        = {2009},
  month       = feb,
  note        = {Version 1.0, released 25 January 2011}
})"},
    {"amd2021fsr1", R"(@misc{amd2021fsr1,
  author       = {{Advanced Micro Devices}},
  title        = {{AMD} {FidelityFX} Super Resolution 1 ({\texttt{ffx\_fsr1.h}}, {\texttt{ffx\_a.h}})},
  howpublished = {Advanced Micro Devices, shader source, \url{https://github.com/GPUOpen-Effects/FidelityFX-FSR}},
  year         = {2021},
  note         = {Version 1.0.2 (commit a21ffb8f), {MIT} licence; {EASU} and {RCAS}}
})"},
    {"amd2023fsr2", R"(@misc{amd2023fsr2,
  author       = {{Advanced Micro Devices}},
  title        = {{AMD} {FidelityFX} Super Resolution 2 ({FSR} 2.2.1: {\texttt{ffx\_fsr2\_*\_pass.glsl}}, {\texttt{ffx\_fsr2.cpp}})},
  howpublished = {Advanced Micro Devices, shader and host source, \url{https://github.com/GPUOpen-Effects/FidelityFX-FSR2}},
  year         = {2023},
  note         = {Version 2.2.1 (commit 1680d1ed), {MIT} licence}
})"},
    {"intel2018cmaa2", R"(@misc{intel2018cmaa2,
  author       = {Filip Strugar},
  title        = {Conservative Morphological Anti-Aliasing 2.0 ({CMAA2}, {\texttt{CMAA2.hlsl}})},
  howpublished = {Intel Corporation, shader source, \url{https://github.com/GameTechDev/CMAA2}},
  year         = {2018},
  note         = {Version 2.3 (commit 071c6b08), Apache-2.0 licence}
})"},
    {"lottes2011fxaa311", R"(@misc{lottes2011fxaa311,
  author       = {Timothy Lottes},
  title        = {{FXAA} 3.11 ({\texttt{Fxaa3\_11.h}}, {FXAA\_PC} quality path)},
  howpublished = {NVIDIA, shader source},
  year         = {2011},
  note         = {Version of 2011-08-12}
})"},
    {"flick2021fxaa", R"(@misc{flick2021fxaa,
  author       = {Jasper Flick},
  title        = {Custom {SRP} 17: {FXAA}},
  howpublished = {Catlike Coding, \url{https://catlikecoding.com/unity/tutorials/custom-srp/fxaa/}},
  year         = {2021},
  note         = {Published 2021-02-28; quality levels low, medium, high and render scale with {FXAA}}
})"},
    {"zeng_fxaa_notes", R"(@misc{zeng_fxaa_notes,
  author       = {WingerZeng},
  title        = {Real-time rendering study notes: {FXAA} (code and step-by-step explanation)},
  howpublished = {Blog post (in Chinese) with a {GLSL} {FXAA} of 12 iterations; renderer \url{https://github.com/WingerZeng/MyCGLab}},
  note         = {Undated}
})"},
    {"jimenez2012smaa", R"(@article{jimenez2012smaa,
  author  = {Jorge Jimenez and Jose I. Echevarria and Tiago Sousa and Diego Gutierrez},
  title   = {{SMAA}: Enhanced Subpixel Morphological Antialiasing},
  journal = {Computer Graphics Forum (Proc. Eurographics)},
  volume  = {31},
  number  = {2},
  pages   = {355--364},
  year    = {2012},
  doi     = {10.1111/j.1467-8659.2012.03014.x}
})"},
    {"d3d11_msaa", R"(@manual{d3d11_msaa,
  author       = {{Microsoft}},
  title        = {Direct3D 11.3 Functional Specification},
  note         = {Section 19.2.4, Standard Multisample Pattern},
  year         = {2015}
})"},
    {"frostkiwi2024aaa", R"(@misc{frostkiwi2024aaa,
  author       = {FrostKiwi},
  title        = {{AAA} -- Analytical Anti-Aliasing},
  howpublished = {FrostKiwi's Secrets, \url{https://blog.frost.kiwi/analytical-anti-aliasing/}},
  year         = {2024},
  note         = {Created 2024-11-20}
})"},
    {"karis2014taa", R"(@inproceedings{karis2014taa,
  author    = {Brian Karis},
  title     = {High Quality Temporal Supersampling},
  booktitle = {Advances in Real-Time Rendering in Games, SIGGRAPH Course},
  year      = {2014}
})"},
    {"salvi2016taa", R"(@inproceedings{salvi2016taa,
  author    = {Marco Salvi},
  title     = {An Excursion in Temporal Supersampling},
  booktitle = {Game Developers Conference},
  year      = {2016}
})"},
    {"tokuyoshi2021gsaa", R"(@article{tokuyoshi2021gsaa,
  author  = {Yusuke Tokuyoshi and Anton S. Kaplanyan},
  title   = {Stable Geometric Specular Antialiasing with Projected-Space {NDF} Filtering},
  journal = {Journal of Computer Graphics Techniques},
  volume  = {10},
  number  = {2},
  year    = {2021}
})"},
    {"wang2004ssim", R"(@article{wang2004ssim,
  author  = {Zhou Wang and Alan C. Bovik and Hamid R. Sheikh and Eero P. Simoncelli},
  title   = {Image Quality Assessment: From Error Visibility to Structural Similarity},
  journal = {IEEE Transactions on Image Processing},
  volume  = {13},
  number  = {4},
  pages   = {600--612},
  year    = {2004}
})"},
    {"andersson2020flip", R"(@article{andersson2020flip,
  author  = {Pontus Andersson and Jim Nilsson and Tomas Akenine-M{\"o}ller and Magnus Oskarsson and Kalle {\AA}str{\"o}m and Mark D. Fairchild},
  title   = {{FLIP}: A Difference Evaluator for Alternating Images},
  journal = {Proceedings of the ACM on Computer Graphics and Interactive Techniques},
  volume  = {3},
  number  = {2},
  pages   = {15:1--15:23},
  year    = {2020}
})"},
    {"watson1986temporal", R"(@incollection{watson1986temporal,
  author    = {Andrew B. Watson},
  title     = {Temporal Sensitivity},
  booktitle = {Handbook of Perception and Human Performance, Vol. 1: Sensory Processes and Perception},
  editor    = {Kenneth R. Boff and Lloyd Kaufman and James P. Thomas},
  chapter   = {6},
  publisher = {Wiley},
  year      = {1986}
})"},
};

}  // namespace

std::string BibEntry(const std::string& key) {
  for (const auto& b : kBibliography) {
    if (key == b.key) return b.entry;
  }
  throw InternalError("no BibTeX entry for source key '" + key + "' (reports/export_bibliography.cpp)");
}

std::vector<std::string> BibKeys() {
  std::vector<std::string> keys;
  for (const auto& b : kBibliography) keys.push_back(b.key);
  return keys;
}

std::vector<std::string> SourceKeys(const std::string& source) {
  std::vector<std::string> keys;
  size_t start = 0;
  while (start < source.size()) {
    const size_t comma = source.find(',', start);
    const std::string key = source.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    if (!key.empty()) keys.push_back(key);
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return keys;
}

std::string BibtexFile(const std::vector<std::pair<std::string, std::string>>& uses,
                       const std::vector<std::string>& provenance) {
  std::string o;
  for (const auto& line : provenance) o += "% " + line + "\n";
  o += "%\n% Sources of the methods and metrics in the exported tables:\n";
  std::vector<std::string> keys;
  for (const auto& [what, source] : uses) {
    const std::vector<std::string> k = SourceKeys(source);
    std::string list;
    for (const auto& key : k) list += (list.empty() ? "" : ", ") + key;
    o += "%   " + what + ": " + (k.empty() ? "no published source (defined by aalab)" : list) + "\n";
    for (const auto& key : k) {
      if (std::find(keys.begin(), keys.end(), key) == keys.end()) keys.push_back(key);
    }
  }
  o += "%   the tool: aalab\n\n";
  for (const auto& key : keys) o += BibEntry(key) + "\n\n";
  o += std::string(
           "@misc{aalab,\n  key          = {aalab},\n"
           "  title        = {aalab: anti-aliasing measured against the truth},\n"
           "  note         = {Version ") +
       AALAB_VERSION + ", commit " + AALAB_GIT_COMMIT + "}\n}\n";
  return o;
}

}  // namespace aalab
