// The rules of each D3D9 shader version as data: one table per version says which
// opcodes it has and what they cost, which register files exist (count, access,
// read ports, indexing) and the ranges their values hold, which modifiers, swizzles
// and write masks are legal, the instruction-slot limits and the flow-control
// nesting limits; and how assembly names each register. The validator checks
// shaders against these tables; the lowering to the exec IR reads the same register
// counts and ranges. What an opcode is, whatever the version: opcode_table.h.
#pragma once
#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>

#include "refx/shader/bytecode.h"

namespace refx::shader {

// Opcode availability and cost in one version. Costs are instruction slots with
// macros expanded (m4x4 = 4, vs_1_1 exp = 10 …); a ps_1_x co-issued pair counts once.
enum OpcodeFlag : uint8_t {
  OpNeedsCap = 1,      // only when the device reports it (ps_2_x/vs_2_x flow control, dsx …)
  OpNoCoissue = 2,     // ps_1_x: cannot be half of a co-issued pair
  OpVectorOnly = 4,    // ps_1_x: may be co-issued only as the .rgb half (dp3)
};
struct OpcodeRule {
  Opcode opcode;
  uint8_t arithmeticSlots = 1;
  uint8_t textureSlots = 0;
  uint8_t flowSlots = 0;
  uint8_t maxPerShader = 0;  // 0 = no limit of its own (ps_1_2 cmp: 3, dp4: 4)
  uint8_t flags = 0;         // OpcodeFlag bits
};

// A register file of one version.
enum RegAccess : uint8_t { RegRead = 1, RegWrite = 2, RegReadWrite = 3 };
enum class CountFromCaps : uint8_t { None, VertexShaderConst, Vs2xTemps, Ps2xTemps };
struct RegisterRule {
  RegType type;
  uint16_t count;        // registers 0..count-1 (the version's minimum when from caps)
  uint8_t access;        // RegAccess bits; a0 is written and used only as an index
  uint8_t readPorts;     // different registers of this file one instruction may read; 0 = no limit
  bool indexable;        // c[a0.x + n], v[aL + n], o[aL + n]
  CountFromCaps fromCaps = CountFromCaps::None;
  const char* meaning = "";  // for messages: "temporary", "constant" …
};

enum class SwizzleRule : uint8_t {
  Ps11,       // none, .a; .b only on alpha-pipe instructions
  Ps14,       // none, .r .g .b .a replicate
  Ps20,       // none, replicate, .yzxw .zxyw .wzyx
  Arbitrary,  // any swizzle
};
enum class WriteMaskRule : uint8_t {
  Ps11,  // .rgba, .rgb, .a
  Any,   // any non-empty subset
};

// Which registers may index (the relative-address register of c[a0.x + n] …).
enum IndexRegister : uint8_t { IndexA0X = 1, IndexA0Any = 2, IndexLoop = 4 };

struct SlotLimits {
  int16_t total = 0;        // 0 = no total limit of its own
  int16_t texture = 0;      // 0 = none
  int16_t arithmetic = 0;   // 0 = none
  bool perPhase = false;    // ps_1_4: texture/arithmetic limits apply to each phase
  bool totalFromCaps = false;  // ps_2_x: NumInstructionSlots
};

struct FlowLimits {
  uint8_t loopDepth = 0;        // rep/loop nesting
  uint8_t callDepth = 0;        // nested calls
  uint8_t staticIfDepth = 0;    // if b#
  uint8_t dynamicDepth = 0;     // if_comp, if p0, callnz p0, break_comp
  uint8_t staticFlowCount = 0;  // if b#, else, rep, loop, call, callnz b#; 0 = no limit
  uint16_t labels = 0;          // l0 .. l(labels-1)
};

struct VersionRules {
  Version version;
  std::string_view name;                    // "ps_1_1"
  std::span<const OpcodeRule> opcodes;
  std::span<const RegisterRule> registers;
  uint16_t srcModifiers;                    // bit n = SrcMod n allowed on arithmetic sources
  uint8_t resultModifiers;                  // ResultMod bits
  int8_t minShift, maxShift;                // ps_1_x _d8.._x8 range; 0, 0 elsewhere
  SwizzleRule swizzles;
  WriteMaskRule writeMasks;
  uint8_t indexRegisters;                   // IndexRegister bits
  SlotLimits slots;
  FlowLimits flow;
  float defMin, defMax;                     // def value range (ps_1_x: [-1, 1])
  bool coissue;                             // ps_1_x `+`
  bool phases;                              // ps_1_4 `phase`
  bool predication;                         // SM2.x (caps) / SM3 `(p0)`
  bool dclInputs;                           // inputs (v#, t#, s#) must be declared before use
  bool scalarReplicate;                     // scalar ops need a replicate swizzle (SM2+)
  uint8_t dependentReadLevels;              // ps_2_0: 4; 0 = no limit
  bool ps30TextureCosts;                    // texld/texkill costs of kPs30TextureCost
  // ps_1_x: r#/t# values hold at least [-minRegisterRange, minRegisterRange] (1 for
  // ps_1_1-1_3, 8 for ps_1_4); the device's PixelShader1xMaxValue may allow more. 0
  // elsewhere: float registers are not clamped. Constants hold [defMin, defMax].
  float minRegisterRange;
  bool colorInputsSaturated;                // v0/v1 read within [0, 1] (ps_1_x-2_x)
};

// The table for a version; nullptr for versions refx does not support (ps_1_0 is
// read as ps_1_1 and vs_1_0 as vs_1_1, as D3D9 does).
const VersionRules* findVersionRules(Version version);
// All tables, in the order vs_1_1 … ps_3_0.
std::span<const VersionRules* const> allVersionRules();

const OpcodeRule* findOpcodeRule(const VersionRules& rules, Opcode op);
const RegisterRule* findRegisterRule(const VersionRules& rules, RegType type);
// Registers of `type` a device running this version may have: the version's count,
// or where the caps set it, the most any version of the same shader type has
// (ps_2_x temps: 32). 0 when the version has no such register file.
uint16_t registerCapacity(const VersionRules& rules, RegType type);

// The one register namer, for listings and messages: "r0", "oT3", "oPos", "vFace",
// "c2049" (CONST2 folded) … The register type alone ("r", "oT", "aL"), as written
// before a relative address: registerTypeName.
std::string registerName(RegType type, uint32_t index, Version version);
std::string_view registerTypeName(RegType type, Version version);

// How assembly writes the registers of one file in a version: a prefix and the
// number, or fixed names by number (oPos, oFog, oPts). The namer above and the
// assembler's register letters read it.
struct RegisterNaming {
  RegType type;
  uint8_t namedIn;                        // bit 0: vertex shaders, bit 1: pixel shaders
  uint8_t fromMajor;                      // the spelling applies from this major version on
  const char* prefix;                     // before the number; "" = fixedNames[0] for every number
  std::array<const char*, 3> fixedNames;  // numbers 0.. with a name of their own
  uint16_t numberOffset;                  // CONST2..4 continue the c# numbers at 2048 …
};
const RegisterNaming* findRegisterNaming(RegType type, Version version);

// ps_3_0 texture-instruction costs that depend on the sampler type and variant.
struct Ps30TextureCost {
  uint8_t texld = 1, texldCube = 4, texldp = 3, texldpCube = 4, texldb = 6, texldl = 2,
          texldlCube = 5, texldd = 3, texkill = 2;
};
inline constexpr Ps30TextureCost kPs30TextureCost{};

}  // namespace refx::shader
