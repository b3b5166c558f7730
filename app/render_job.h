// What render, bench and demo share: turning --scene/--technique/--set into a scene and parameter
// values (bad input -> UsageError), and the JSON record of a run (DESIGN.md, "Speed against error").
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/image.h"
#include "core/scene.h"
#include "gl/context/context.h"
#include "gl/renderer.h"
#include "gl/technique/technique.h"

namespace bounce::app {

// Loads a built-in scene by name, a glTF file or a scene setup (.json) by path; any failure becomes a
// UsageError.
core::Scene loadSceneForCli(const std::string& nameOrPath);

// --camera and --light (repeatable) for render, reference, demo and bench: the help text and their use.
extern const char* const kSceneOptionsHelp;
// Applies them to the scene (UsageError on bad input), then says where the camera came from and warns on
// standard error when the scene has no light at all (a black image otherwise, without a word).
void applySceneOptions(core::Scene& scene, const std::string& camera, const std::vector<std::string>& lights);

// Applies "key=value" settings to the frame's or the technique's parameters; UsageError on bad input.
void applySets(const std::vector<std::string>& sets, const gl::TechniqueInfo& technique, gl::ParamValues& frameValues,
               gl::ParamValues& techniqueValues);

// --technique NAME and its --set values: the registry's entry, and the frame's and the technique's
// parameters at their defaults with the sets applied. An unknown technique or a bad set is a UsageError.
struct CliTechnique {
    const gl::TechniqueInfo* info = nullptr;
    gl::ParamValues frameValues, techniqueValues;
};
CliTechnique techniqueForCli(const std::string& name, const std::vector<std::string>& sets);

// Creates the context for --backend; a missing 4.5 core context is a UsageError (exit 2).
std::unique_ptr<gl::Context> createContextForCli(const std::string& backend, bool window = false);

// The renderer of `render` (a still image or a sequence): a technique that refuses its parameters
// (std::invalid_argument when it is made) is a UsageError (exit 2); the indirect scale set (1..16).
std::unique_ptr<gl::Renderer> makeRendererForCli(const core::Scene& scene, const std::string& technique,
                                                 const gl::ParamValues& frameValues,
                                                 const gl::ParamValues& techniqueValues, int width, int height,
                                                 int indirectScale);

// The run's record: backend, renderer, size, technique, parameters, per-pass GPU ms, counters, bytes.
nlohmann::json runRecord(const gl::ContextInfo& context, const std::string& scene, gl::Renderer& renderer);

// Values (channels) of the image that are NaN or +-Inf. A run whose image has any must never look like a
// good one: its record says how many, its error figures are infinite, and the command exits with status 1.
std::size_t nonFiniteValues(const core::Image& image);

// The record as text: JSON has no infinity, so +-inf is written as the string "inf" / "-inf" (Python's
// float() reads it) and NaN as null, as `bounce compare --json` does; every other value as dump(2).
std::string recordText(const nlohmann::json& record);

// Prints the per-pass table (median ms over the timed frames) to stdout, with each pass's bound and
// efficiency when this renderer's ceilings are cached (`bounce probe`).
void printPassTable(gl::Renderer& renderer, const std::string& glRenderer);

} // namespace bounce::app
