// The D3D9 shader token format (bytecode.md): encode() and a
// bounds-checked decode() that names the offending token for any malformed input.
#include "refx/shader/bytecode.h"

#include <cstring>

#include "refx/core/diagnostics.h"
#include "refx/shader/opcode_table.h"

namespace refx::shader {

namespace {

constexpr uint32_t kParamBit = 0x80000000u;      // bit 31 of every parameter token
constexpr uint32_t kRelativeBit = 0x00002000u;   // bit 13: relative addressing
constexpr uint32_t kPredicatedBit = 0x10000000u; // D3DSHADER_INSTRUCTION_PREDICATED
constexpr uint32_t kCoissueBit = 0x40000000u;    // D3DSI_COISSUE
constexpr uint32_t kEndToken = 0x0000FFFFu;
constexpr uint32_t kPhaseToken = 0x0000FFFDu;
constexpr int kLastRegType = int(RegType::Predicate);

// Number of literal DWORDs after the destination of def/defi/defb.
int literalCount(Opcode op) {
  const OpcodeInfo* info = findOpcode(op);
  return info ? info->literals : 0;
}

bool validVersion(Version v) {
  if (v.isVertex()) {
    if (v.major == 1) return v.minor <= 1;
  } else if (v.major == 1) {
    return v.minor <= 4;
  }
  if (v.major == 2) return v.minor == 0 || v.minor == 1 || v.minor == 0xFF;
  if (v.major == 3) return v.minor == 0 || v.minor == 0xFF;
  return false;
}

// Register type field split over bits 30:28 (low 3 bits) and 12:11 (high 2 bits).
uint32_t regTypeBits(RegType type) {
  uint32_t t = uint32_t(type);
  return ((t & 7u) << 28) | ((t & 0x18u) << 8);
}
int regTypeOf(uint32_t tok) { return int(((tok >> 28) & 7u) | ((tok >> 8) & 0x18u)); }

// c2048.. are written as CONST2..CONST4 with the number relative to the bank.
uint32_t regBits(RegType type, uint32_t index) {
  if (type == RegType::Const && index >= 2048) {
    uint32_t bank = index / 2048;  // 1..3
    type = RegType(uint32_t(RegType::Const2) + bank - 1);
    index -= bank * 2048;
  }
  return kParamBit | regTypeBits(type) | (index & 0x7FFu);
}

uint32_t relativeToken(const RelativeAddress& rel) {
  // a0 selects its component with a replicate swizzle; aL is written with .xyzw.
  uint32_t swizzle = rel.type == RegType::Loop ? 0xE4u : (rel.component & 3u) * 0x55u;
  return kParamBit | regTypeBits(rel.type) | (swizzle << 16);
}

class Encoder {
 public:
  explicit Encoder(const Shader& s) : shader_(s), sm2_(s.version.sm2plus()) {}

  std::vector<uint32_t> run() {
    out_.push_back(shader_.version.token());
    for (size_t i = 0; i < shader_.instructions.size(); ++i) instruction(shader_.instructions[i], i);
    out_.push_back(kEndToken);
    return std::move(out_);
  }

 private:
  void instruction(const Instruction& ins, size_t n) {
    if (ins.opcode == Opcode::Comment) {
      if (ins.comment.size() > 0x7FFF) fail("instruction {}: a comment holds at most 32767 DWORDs", n);
      out_.push_back(0xFFFEu | uint32_t(ins.comment.size()) << 16);
      out_.insert(out_.end(), ins.comment.begin(), ins.comment.end());
      return;
    }
    if (ins.opcode == Opcode::Phase) {
      out_.push_back(kPhaseToken);
      return;
    }
    if (ins.opcode == Opcode::End || !findOpcode(ins.opcode))
      fail("instruction {}: opcode {} cannot be encoded", n, unsigned(ins.opcode));
    const size_t head = out_.size();
    out_.push_back(0);
    const OperandCounts counts = operandCounts(ins.opcode, shader_.version);
    if (ins.opcode == Opcode::Dcl) {
      out_.push_back(kParamBit | (uint32_t(ins.usage) & 0xFu) | (uint32_t(ins.usageIndex) & 0xFu) << 16 |
                     (uint32_t(ins.textureType) & 0xFu) << 27);
    }
    if (counts.dst) dst(ins.dst);
    if (ins.predicated) {
      out_.push_back(kParamBit | regTypeBits(RegType::Predicate) | uint32_t(ins.predicateSwizzle) << 16 |
                     (ins.predicateNot ? uint32_t(SrcMod::Not) << 24 : 0u));
    }
    const int lits = literalCount(ins.opcode);
    for (int i = 0; i < lits; ++i) out_.push_back(ins.literal[i]);
    for (int i = 0; i < counts.src; ++i) src(ins.src[i]);

    uint32_t tok = uint32_t(ins.opcode) | uint32_t(ins.control) << 16;
    if (sm2_) {
      size_t length = out_.size() - head - 1;
      if (length > 15) fail("instruction {}: {} parameter tokens do not fit the length field", n, length);
      tok |= uint32_t(length) << 24;
    }
    if (ins.predicated) tok |= kPredicatedBit;
    if (ins.coissue) tok |= kCoissueBit;
    out_[head] = tok;
  }

  void dst(const DstParam& d) {
    uint32_t tok = regBits(d.type, d.index) | uint32_t(d.writeMask & 0xF) << 16 |
                   uint32_t(d.resultMod & 0xF) << 20 | (uint32_t(d.shift) & 0xFu) << 24;
    if (d.relative) tok |= kRelativeBit;
    out_.push_back(tok);
    if (d.relative && sm2_) out_.push_back(relativeToken(d.rel));
  }

  void src(const SrcParam& s) {
    uint32_t tok = regBits(s.type, s.index) | uint32_t(s.swizzle) << 16 | (uint32_t(s.mod) & 0xFu) << 24;
    // vs_1_1 marks c[a0.x + n] with bit 13 alone; SM2+ adds the address token.
    if (s.relative) tok |= kRelativeBit;
    out_.push_back(tok);
    if (s.relative && sm2_) out_.push_back(relativeToken(s.rel));
  }

  const Shader& shader_;
  bool sm2_;
  std::vector<uint32_t> out_;
};

class Decoder {
 public:
  explicit Decoder(std::span<const uint32_t> t) : t_(t) {}

  Shader run() {
    Shader s;
    if (t_.empty()) fail("token 0: expected a version token (0xFFFE#### or 0xFFFF####), found no data");
    const uint32_t v = t_[0];
    if ((v >> 16) != 0xFFFE && (v >> 16) != 0xFFFF)
      fail("token 0: expected a version token (0xFFFE#### vertex or 0xFFFF#### pixel), found 0x{:08X}", v);
    s.version = Version::fromToken(v);
    if (!validVersion(s.version))
      fail("token 0: expected a shader version (vs_1_1..vs_3_0, ps_1_1..ps_3_0), found 0x{:08X}", v);
    version_ = s.version;
    sm2_ = version_.sm2plus();
    pos_ = 1;
    for (;;) {
      if (pos_ >= t_.size())
        fail("token {}: expected an instruction or the end token 0x0000FFFF, found the end of the data", pos_);
      const size_t at = pos_;
      const uint32_t tok = t_[pos_++];
      if (tok == kEndToken) break;
      if (tok & kParamBit)
        fail("token {}: expected an instruction token (bit 31 clear), found parameter token 0x{:08X}", at, tok);
      const uint32_t op = tok & 0xFFFFu;
      if (op == 0xFFFEu) {
        comment(s, tok, at);
        continue;
      }
      if (op == 0xFFFFu || op == 0xFFFDu) {
        if (op == 0xFFFFu || tok != kPhaseToken)
          fail("token {}: expected {} token 0x{:08X} with no other bits, found 0x{:08X}", at,
               op == 0xFFFFu ? "the end" : "a phase", op, tok);
        Instruction ins;
        ins.opcode = Opcode::Phase;
        s.instructions.push_back(std::move(ins));
        continue;
      }
      s.instructions.push_back(instruction(tok, at));
    }
    return s;
  }

 private:
  uint32_t next(size_t at, const char* what) {
    if (pos_ >= limit_)
      fail("token {}: expected {} of the instruction at token {}, found the end of the {}", pos_, what, at,
           limit_ == t_.size() ? "data" : "instruction (length field)");
    return t_[pos_++];
  }

  uint32_t param(size_t at, const char* what) {
    const size_t here = pos_;
    uint32_t tok = next(at, what);
    if (!(tok & kParamBit)) fail("token {}: expected {} (bit 31 set), found 0x{:08X}", here, what, tok);
    return tok;
  }

  void comment(Shader& s, uint32_t tok, size_t at) {
    const size_t size = (tok >> 16) & 0x7FFFu;
    if (size > t_.size() - pos_)
      fail("token {}: expected a comment of {} DWORDs, found only {} DWORDs left", at, size, t_.size() - pos_);
    Instruction ins;
    ins.opcode = Opcode::Comment;
    ins.comment.assign(t_.begin() + pos_, t_.begin() + pos_ + size);
    pos_ += size;
    s.instructions.push_back(std::move(ins));
  }

  // Register type and number, CONST2..4 folded into Const.
  void reg(uint32_t tok, size_t here, RegType& type, uint16_t& index, const char* what) {
    int t = regTypeOf(tok);
    if (t > kLastRegType)
      fail("token {}: expected a register type 0..{} in {}, found {}", here, kLastRegType, what, t);
    index = uint16_t(tok & 0x7FFu);
    type = RegType(t);
    if (type == RegType::Const2 || type == RegType::Const3 || type == RegType::Const4) {
      index = uint16_t(index + 2048 * (t - int(RegType::Const2) + 1));
      type = RegType::Const;
    }
  }

  RelativeAddress relative(size_t at) {
    const size_t here = pos_;
    uint32_t tok = param(at, "a relative-address token");
    RelativeAddress rel;
    int t = regTypeOf(tok);
    if (t != int(RegType::Addr) && t != int(RegType::Loop))
      fail("token {}: expected a relative-address token of type a0 (3) or aL (15), found type {}", here, t);
    rel.type = RegType(t);
    rel.component = rel.type == RegType::Addr ? uint8_t((tok >> 16) & 3u) : 0;
    return rel;
  }

  DstParam dst(size_t at) {
    const size_t here = pos_;
    uint32_t tok = param(at, "a destination token");
    DstParam d;
    reg(tok, here, d.type, d.index, "the destination");
    d.writeMask = uint8_t((tok >> 16) & 0xFu);
    d.resultMod = uint8_t((tok >> 20) & 0xFu);
    d.shift = int8_t(int8_t(uint8_t((tok >> 24) & 0xFu) << 4) >> 4);
    if (tok & kRelativeBit) {
      d.relative = true;
      if (sm2_) d.rel = relative(at);
    }
    return d;
  }

  SrcParam src(size_t at) {
    const size_t here = pos_;
    uint32_t tok = param(at, "a source token");
    SrcParam s;
    reg(tok, here, s.type, s.index, "a source");
    s.swizzle = uint8_t((tok >> 16) & 0xFFu);
    uint32_t mod = (tok >> 24) & 0xFu;
    if (mod > uint32_t(SrcMod::Not)) fail("token {}: expected a source modifier 0..13, found {}", here, mod);
    s.mod = SrcMod(mod);
    if (tok & kRelativeBit) {
      s.relative = true;
      if (sm2_) s.rel = relative(at);  // vs_1_1: implicitly a0.x, no extra token
    }
    return s;
  }

  Instruction instruction(uint32_t tok, size_t at) {
    Instruction ins;
    const uint32_t op = tok & 0xFFFFu;
    const OpcodeInfo* info = findOpcode(Opcode(op));
    if (!info) fail("token {}: expected a known opcode, found {} (0x{:08X})", at, op, tok);
    ins.opcode = Opcode(op);
    ins.control = uint8_t((tok >> 16) & 0xFFu);
    ins.coissue = (tok & kCoissueBit) != 0;
    ins.predicated = (tok & kPredicatedBit) != 0;
    if (ins.predicated && !sm2_)
      fail("token {}: expected no predicate bit (28) before shader model 2, found 0x{:08X}", at, tok);
    // SM2+ bounds the instruction by its length field; SM1 by the opcode's operand count.
    size_t length = 0;
    if (sm2_) {
      length = (tok >> 24) & 0xFu;
      if (length > t_.size() - pos_)
        fail("token {}: expected {} parameter tokens (length field), found only {} DWORDs left", at, length,
             t_.size() - pos_);
      limit_ = pos_ + length;
    } else {
      limit_ = t_.size();
    }
    const size_t first = pos_;
    const OperandCounts counts = operandCounts(ins.opcode, version_);
    if (ins.opcode == Opcode::Dcl) {
      uint32_t usage = param(at, "a dcl usage token");
      ins.usage = DeclUsage(usage & 0xFu);
      ins.usageIndex = uint8_t((usage >> 16) & 0xFu);
      ins.textureType = TextureType((usage >> 27) & 0xFu);
    }
    if (counts.dst) {
      ins.hasDst = true;
      ins.dst = dst(at);
    }
    if (ins.predicated) {
      const size_t here = pos_;
      uint32_t p = param(at, "a predicate token");
      if (regTypeOf(p) != int(RegType::Predicate))
        fail("token {}: expected a predicate token of type p0 (19), found type {}", here, regTypeOf(p));
      uint32_t mod = (p >> 24) & 0xFu;
      if (mod != uint32_t(SrcMod::None) && mod != uint32_t(SrcMod::Not))
        fail("token {}: expected predicate modifier none or ! (13), found {}", here, mod);
      ins.predicateNot = mod == uint32_t(SrcMod::Not);
      ins.predicateSwizzle = uint8_t((p >> 16) & 0xFFu);
    }
    const int lits = literalCount(ins.opcode);
    for (int i = 0; i < lits; ++i) ins.literal[i] = next(at, "a literal value");
    ins.srcCount = uint8_t(counts.src);
    for (int i = 0; i < counts.src; ++i) ins.src[i] = src(at);
    if (sm2_ && pos_ - first != length)
      fail("token {}: expected {} parameter tokens for {} (length field), found {}", at, length, info->name,
           pos_ - first);
    limit_ = t_.size();
    return ins;
  }

  std::span<const uint32_t> t_;
  Version version_;
  bool sm2_ = false;
  size_t pos_ = 0;
  size_t limit_ = 0;
};

}  // namespace

std::string Version::name() const {
  std::string s = isVertex() ? "vs_" : "ps_";
  s += std::to_string(major);
  s += '_';
  if (minor == 0xFF) s += "sw";
  else if (major == 2 && minor == 1) s += 'x';
  else s += std::to_string(minor);
  return s;
}

Shader decode(std::span<const uint32_t> tokens) { return Decoder(tokens).run(); }

std::vector<uint32_t> tokensFromBytes(std::span<const uint8_t> bytes) {
  if (bytes.size() % 4 != 0)
    fail("byte {}: expected whole 32-bit tokens, the data is {} bytes (not a multiple of 4)",
         bytes.size() - bytes.size() % 4, bytes.size());
  std::vector<uint32_t> out(bytes.size() / 4);
  for (size_t i = 0; i < out.size(); ++i) {
    const uint8_t* b = bytes.data() + 4 * i;
    out[i] = uint32_t(b[0]) | uint32_t(b[1]) << 8 | uint32_t(b[2]) << 16 | uint32_t(b[3]) << 24;
  }
  return out;
}

std::vector<uint32_t> encode(const Shader& shader) { return Encoder(shader).run(); }

}  // namespace refx::shader
