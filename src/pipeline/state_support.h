// Which D3D9 render, texture stage and sampler states refx implements. Device's
// Set*State refuses a value other than the D3D9 default for a state refx stores but
// does not act on, so no state is ever silently ignored. docs/device_states.md is
// the same table in prose (a test keeps the two in step).
#pragma once
#include <cstdint>
#include <span>
#include <string>
#include <string_view>

namespace refx::pipeline {

enum class StateClass { Render, TextureStage, Sampler };

enum class StateSupport {
  Implemented,  // the device follows every value
  NoEffect,     // every value accepted: D3D9 gives it no effect on what refx renders
  DefaultOnly,  // only the D3D9 default is accepted; other values are errors
};

struct StateSupportEntry {
  StateClass stateClass;
  uint32_t state;            // D3DRS_*, D3DTSS_*, D3DSAMP_* value
  StateSupport support;
  std::string_view where;    // the code that implements it, or why it is accepted/refused
};

std::span<const StateSupportEntry> stateSupportTable();
// nullptr for a number that is no D3D9 state.
const StateSupportEntry* findStateSupport(StateClass stateClass, uint32_t state);
// "D3DRS_ZENABLE"; a plain number for an unnamed state.
std::string stateDisplayName(StateClass stateClass, uint32_t state);
// Throws refx::Error "D3DRS_X is not implemented by refx (...)" when `value` differs
// from the D3D9 default of a DefaultOnly state, and for a nonzero value of a number
// that is no D3D9 state.
void requireImplementedState(StateClass stateClass, uint32_t state, uint32_t value);

}  // namespace refx::pipeline
