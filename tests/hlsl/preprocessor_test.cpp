// The HLSL preprocessor: tokens, positions and diagnostics, every expected value
// worked out by hand from the C preprocessor rules.
#include "hlsl/preprocessor.h"

#include <gtest/gtest.h>

#include <chrono>
#include <string>
#include <vector>

using namespace refx;
using namespace refx::hlsl;
using namespace refx::hlsl::detail;

namespace {

const std::string kIncludeDir = std::string(REFX_TEST_DIR) + "/hlsl/pp_include";

struct Result {
  std::vector<Token> tokens;
  DiagnosticSink sink;

  // Token texts without the final EndOfFile.
  std::vector<std::string> texts() const {
    std::vector<std::string> v;
    for (size_t i = 0; i + 1 < tokens.size(); ++i) v.push_back(tokens[i].text);
    return v;
  }
  // Every diagnostic as "CODE@line:col".
  std::vector<std::string> diagnostics() const {
    std::vector<std::string> v;
    for (const Diagnostic& d : sink.all())
      v.push_back(d.code + "@" + std::to_string(d.where.line) + ":" + std::to_string(d.where.column));
    return v;
  }
};

Result run(std::string_view source, const PreprocessOptions& options = {}, std::string_view fileName = "t.hlsl") {
  Result r;
  r.tokens = preprocess(source, fileName, options, r.sink);
  return r;
}

void expectToken(const Token& t, TokenKind kind, const std::string& text, int line, int column) {
  EXPECT_EQ(t.kind, kind) << "token '" << t.text << "'";
  EXPECT_EQ(t.text, text);
  EXPECT_EQ(t.line, line) << "token '" << t.text << "'";
  EXPECT_EQ(t.column, column) << "token '" << t.text << "'";
}

using Texts = std::vector<std::string>;
using Codes = std::vector<std::string>;

// ---- lexing --------------------------------------------------------------------

TEST(HlslLexer, IdentifiersAndLongestMatchPunctuators) {
  const Result r = run("a<<=b>>=c a+++b x->y::z");
  ASSERT_EQ(r.tokens.size(), 15u);
  expectToken(r.tokens[0], TokenKind::Identifier, "a", 1, 1);
  expectToken(r.tokens[1], TokenKind::Punct, "<<=", 1, 2);
  expectToken(r.tokens[2], TokenKind::Identifier, "b", 1, 5);
  expectToken(r.tokens[3], TokenKind::Punct, ">>=", 1, 6);
  expectToken(r.tokens[4], TokenKind::Identifier, "c", 1, 9);
  expectToken(r.tokens[5], TokenKind::Identifier, "a", 1, 11);
  expectToken(r.tokens[6], TokenKind::Punct, "++", 1, 12);
  expectToken(r.tokens[7], TokenKind::Punct, "+", 1, 14);
  expectToken(r.tokens[8], TokenKind::Identifier, "b", 1, 15);
  expectToken(r.tokens[9], TokenKind::Identifier, "x", 1, 17);
  expectToken(r.tokens[10], TokenKind::Punct, "->", 1, 18);
  expectToken(r.tokens[11], TokenKind::Identifier, "y", 1, 20);
  expectToken(r.tokens[12], TokenKind::Punct, "::", 1, 21);
  expectToken(r.tokens[13], TokenKind::Identifier, "z", 1, 23);
  EXPECT_EQ(r.tokens[14].kind, TokenKind::EndOfFile);
  EXPECT_TRUE(r.sink.all().empty());
}

TEST(HlslLexer, EveryPunctuator) {
  const Result r = run("++ -- += -= *= /= %= &= |= ^= && || == != <= >= << >> :: -> <<= >>= "
                       "( ) { } [ ] ; , . : ? + - * / % & | ^ ~ ! = < >");
  EXPECT_EQ(r.texts(), (Texts{"++", "--", "+=", "-=", "*=", "/=", "%=", "&=", "|=", "^=", "&&", "||",
                              "==", "!=", "<=", ">=", "<<", ">>", "::", "->", "<<=", ">>=", "(", ")",
                              "{", "}", "[", "]", ";", ",", ".", ":", "?", "+", "-", "*", "/", "%",
                              "&", "|", "^", "~", "!", "=", "<", ">"}));
  for (size_t i = 0; i + 1 < r.tokens.size(); ++i) EXPECT_EQ(r.tokens[i].kind, TokenKind::Punct);
  EXPECT_TRUE(r.sink.all().empty());
}

TEST(HlslLexer, IntLiterals) {
  const Result r = run("12 0x1F 017 12u 12L 0XABul 7U 0");
  EXPECT_EQ(r.texts(), (Texts{"12", "0x1F", "017", "12u", "12L", "0XABul", "7U", "0"}));
  for (size_t i = 0; i + 1 < r.tokens.size(); ++i) EXPECT_EQ(r.tokens[i].kind, TokenKind::IntLiteral);
  expectToken(r.tokens[5], TokenKind::IntLiteral, "0XABul", 1, 21);
}

TEST(HlslLexer, FloatLiterals) {
  const Result r = run("1.0 .5 1. 1e-3 1.5e+2f 2.h 3.5H 1.0L 1E5 .25F");
  ASSERT_EQ(r.tokens.size(), 11u);
  expectToken(r.tokens[0], TokenKind::FloatLiteral, "1.0", 1, 1);
  expectToken(r.tokens[1], TokenKind::FloatLiteral, ".5", 1, 5);
  expectToken(r.tokens[2], TokenKind::FloatLiteral, "1.", 1, 8);
  expectToken(r.tokens[3], TokenKind::FloatLiteral, "1e-3", 1, 11);
  expectToken(r.tokens[4], TokenKind::FloatLiteral, "1.5e+2f", 1, 16);
  expectToken(r.tokens[5], TokenKind::FloatLiteral, "2.h", 1, 24);
  expectToken(r.tokens[6], TokenKind::FloatLiteral, "3.5H", 1, 28);
  expectToken(r.tokens[7], TokenKind::FloatLiteral, "1.0L", 1, 33);
  expectToken(r.tokens[8], TokenKind::FloatLiteral, "1E5", 1, 38);
  expectToken(r.tokens[9], TokenKind::FloatLiteral, ".25F", 1, 42);
}

TEST(HlslLexer, ExponentWithoutDigitsIsNoExponent) {
  // "1e+x": the 'e' is not followed by digits, so 1 is an integer and e a name.
  const Result r = run("1e+x");
  ASSERT_EQ(r.tokens.size(), 5u);
  expectToken(r.tokens[0], TokenKind::IntLiteral, "1", 1, 1);
  expectToken(r.tokens[1], TokenKind::Identifier, "e", 1, 2);
  expectToken(r.tokens[2], TokenKind::Punct, "+", 1, 3);
  expectToken(r.tokens[3], TokenKind::Identifier, "x", 1, 4);
}

TEST(HlslLexer, StringLiteralEscapesResolved) {
  const Result r = run(R"(x "a\tb\\c\"d\x41\101\n" y)");
  ASSERT_EQ(r.tokens.size(), 4u);
  expectToken(r.tokens[1], TokenKind::StringLiteral, "a\tb\\c\"dAA\n", 1, 3);
  expectToken(r.tokens[2], TokenKind::Identifier, "y", 1, 26);
}

TEST(HlslLexer, CommentsAndTabs) {
  const Result r = run("a /* x\n y */ b // c */ d\n\td");
  ASSERT_EQ(r.tokens.size(), 4u);
  expectToken(r.tokens[0], TokenKind::Identifier, "a", 1, 1);
  expectToken(r.tokens[1], TokenKind::Identifier, "b", 2, 7);
  expectToken(r.tokens[2], TokenKind::Identifier, "d", 3, 2);  // a tab is one column
  expectToken(r.tokens[3], TokenKind::EndOfFile, "", 3, 3);
}

TEST(HlslLexer, LineContinuationsEverywhere) {
  // Inside a name, inside a // comment (which then swallows the next line), with CRLF.
  const Result r = run("ab\\\ncd e // c\\\nhidden\nf\\\r\ng");
  ASSERT_EQ(r.tokens.size(), 4u);
  expectToken(r.tokens[0], TokenKind::Identifier, "abcd", 1, 1);
  expectToken(r.tokens[1], TokenKind::Identifier, "e", 2, 4);
  expectToken(r.tokens[2], TokenKind::Identifier, "fg", 4, 1);
}

TEST(HlslLexer, CrLfLineEnds) {
  const Result r = run("a\r\n  b\r\n");
  ASSERT_EQ(r.tokens.size(), 3u);
  expectToken(r.tokens[1], TokenKind::Identifier, "b", 2, 3);
  expectToken(r.tokens[2], TokenKind::EndOfFile, "", 3, 1);
}

TEST(HlslLexer, LexicalErrorsAreReportedAndLexingGoesOn) {
  const Result r = run("a @ b\n\"open\nc /* never closed");
  EXPECT_EQ(r.diagnostics(), (Codes{"X1553@1:3", "X1552@2:1", "X1551@3:3"}));
  ASSERT_EQ(r.tokens.size(), 5u);
  expectToken(r.tokens[0], TokenKind::Identifier, "a", 1, 1);
  expectToken(r.tokens[1], TokenKind::Identifier, "b", 1, 5);
  expectToken(r.tokens[2], TokenKind::StringLiteral, "open", 2, 1);
  expectToken(r.tokens[3], TokenKind::Identifier, "c", 3, 1);
}

// ---- macros --------------------------------------------------------------------

TEST(HlslPreprocessor, ObjectMacroTakesTheLocationOfItsUse) {
  const Result r = run("#define N 4\nint a[N];");
  ASSERT_EQ(r.tokens.size(), 7u);
  expectToken(r.tokens[0], TokenKind::Identifier, "int", 2, 1);
  expectToken(r.tokens[3], TokenKind::IntLiteral, "4", 2, 7);
  expectToken(r.tokens[4], TokenKind::Punct, "]", 2, 8);
  EXPECT_EQ(r.tokens[3].file, "t.hlsl");
  EXPECT_TRUE(r.sink.all().empty());
}

TEST(HlslPreprocessor, FunctionMacro) {
  const Result r = run("#define ADD(a, b) ((a) + (b))\n  ADD(1, 2*3)");
  EXPECT_EQ(r.texts(), (Texts{"(", "(", "1", ")", "+", "(", "2", "*", "3", ")", ")"}));
  for (size_t i = 0; i + 1 < r.tokens.size(); ++i) {
    EXPECT_EQ(r.tokens[i].line, 2);
    EXPECT_EQ(r.tokens[i].column, 3);
  }
}

TEST(HlslPreprocessor, EmptyArguments) {
  const Result r = run("#define F(x) [x]\n#define G() 7\n#define H(a,b) a|b\nF() G() H(,)");
  EXPECT_EQ(r.texts(), (Texts{"[", "]", "7", "|"}));
  EXPECT_TRUE(r.sink.all().empty());
}

TEST(HlslPreprocessor, ArgumentsWithParenthesesAndCommas) {
  const Result r = run("#define FIRST(a, b) a\nFIRST((1, 2), 3)");
  EXPECT_EQ(r.texts(), (Texts{"(", "1", ",", "2", ")"}));
}

TEST(HlslPreprocessor, FunctionMacroNameWithoutParenthesesIsAName) {
  const Result r = run("#define F(x) x\nF + F(2)");
  EXPECT_EQ(r.texts(), (Texts{"F", "+", "2"}));
}

TEST(HlslPreprocessor, ArgumentsSpanLines) {
  const Result r = run("#define F(x, y) y x\nF(a,\n  b)\nc");
  ASSERT_EQ(r.tokens.size(), 4u);
  expectToken(r.tokens[0], TokenKind::Identifier, "b", 2, 1);
  expectToken(r.tokens[1], TokenKind::Identifier, "a", 2, 1);
  expectToken(r.tokens[2], TokenKind::Identifier, "c", 4, 1);
}

TEST(HlslPreprocessor, NestedExpansion) {
  const Result r = run("#define A B+1\n#define B C*2\n#define C 5\nA");
  EXPECT_EQ(r.texts(), (Texts{"5", "*", "2", "+", "1"}));
}

TEST(HlslPreprocessor, ArgumentsAreExpandedFirst) {
  const Result r = run("#define ONE 1\n#define ID(x) x\n#define TWICE(x) x x\nID(ONE) TWICE(ID(ONE))");
  EXPECT_EQ(r.texts(), (Texts{"1", "1", "1"}));
}

TEST(HlslPreprocessor, SelfReferenceIsNotExpandedAgain) {
  const Result r = run("#define foo foo+1\nfoo\n#define x y\n#define y x\nx y\n#define f(a) a + f(a)\nf(2)");
  // foo → foo+1 with foo painted; x → y → x (stops); y → x → y (stops);
  // f(2) → 2 + f(2), the inner f painted.
  EXPECT_EQ(r.texts(), (Texts{"foo", "+", "1", "x", "y", "2", "+", "f", "(", "2", ")"}));
  EXPECT_TRUE(r.sink.all().empty());
}

TEST(HlslPreprocessor, PaintedNameStaysUnexpandedWhenPassedOn) {
  // g → f(g); the g inside is painted (it came out of g), so ID's rescan keeps it.
  const Result r = run("#define ID(x) x\n#define g ID(g)\ng");
  EXPECT_EQ(r.texts(), (Texts{"g"}));
}

TEST(HlslPreprocessor, MacroFromRescanTakesArgumentsFromTheSource) {
  // The expansion of CALL ends in the name F; its ( ) come from the text after it.
  const Result r = run("#define F(x) <x>\n#define CALL F\nCALL(3)");
  EXPECT_EQ(r.texts(), (Texts{"<", "3", ">"}));
}

TEST(HlslPreprocessor, Stringizing) {
  const Result r = run("#define S(x) #x\nS(a  +  \"q\\n\") S() S( spaced   out )");
  ASSERT_EQ(r.tokens.size(), 4u);
  expectToken(r.tokens[0], TokenKind::StringLiteral, "a + \"q\\n\"", 2, 1);
  expectToken(r.tokens[1], TokenKind::StringLiteral, "", 2, 16);
  expectToken(r.tokens[2], TokenKind::StringLiteral, "spaced out", 2, 20);
}

TEST(HlslPreprocessor, StringizingDoesNotExpandTheArgument) {
  const Result r = run("#define N 4\n#define S(x) #x\n#define XS(x) S(x)\nS(N) XS(N)");
  EXPECT_EQ(r.texts(), (Texts{"N", "4"}));
  EXPECT_EQ(r.tokens[0].kind, TokenKind::StringLiteral);
}

TEST(HlslPreprocessor, TokenPasting) {
  //                                  col: 1        11        21       30
  const Result r = run("#define CAT(a, b) a##b\nCAT(x, 1) CAT(+, =) CAT(, y) CAT(1., 5e2f)");
  ASSERT_EQ(r.tokens.size(), 5u);
  expectToken(r.tokens[0], TokenKind::Identifier, "x1", 2, 1);
  expectToken(r.tokens[1], TokenKind::Punct, "+=", 2, 11);
  expectToken(r.tokens[2], TokenKind::Identifier, "y", 2, 21);
  expectToken(r.tokens[3], TokenKind::FloatLiteral, "1.5e2f", 2, 30);
  EXPECT_TRUE(r.sink.all().empty());
}

TEST(HlslPreprocessor, PastedNameIsExpandedButOperandsAreNot) {
  const Result r = run("#define XY 42\n#define X 1\n#define CAT(a, b) a ## b\n#define MID(a) _ ## a ## _\nCAT(X, Y) CAT(X, ) MID(X)");
  EXPECT_EQ(r.texts(), (Texts{"42", "1", "_X_"}));
}

TEST(HlslPreprocessor, PastingThatGivesNoTokenIsAnError) {
  const Result r = run("#define P(a, b) a##b\nint P(+, /);");
  EXPECT_EQ(r.diagnostics(), (Codes{"X1564@2:5"}));
  EXPECT_EQ(r.texts(), (Texts{"int", "+", "/", ";"}));
}

TEST(HlslPreprocessor, LineInsideAMacroIsTheLineOfUse) {
  const Result r = run("#define HERE __LINE__\n#define TWICE(x) x x\n\nint a = HERE;\nTWICE(HERE)\n__LINE__");
  ASSERT_EQ(r.tokens.size(), 9u);
  expectToken(r.tokens[3], TokenKind::IntLiteral, "4", 4, 9);
  expectToken(r.tokens[5], TokenKind::IntLiteral, "5", 5, 1);
  expectToken(r.tokens[6], TokenKind::IntLiteral, "5", 5, 1);
  expectToken(r.tokens[7], TokenKind::IntLiteral, "6", 6, 1);
}

TEST(HlslPreprocessor, FileMacro) {
  const Result r = run("__FILE__", {}, "dir\\s.hlsl");
  ASSERT_EQ(r.tokens.size(), 2u);
  expectToken(r.tokens[0], TokenKind::StringLiteral, "dir\\s.hlsl", 1, 1);
}

TEST(HlslPreprocessor, UndefAndRedefinition) {
  const Result r = run("#define A 1\n#undef A\nA\n#define B 1\n#define B  1\n#define B 2\nB");
  // Identical redefinition (whitespace amounts aside) is silent; a different one warns.
  EXPECT_EQ(r.diagnostics(), (Codes{"X1519@6:9"}));
  EXPECT_EQ(r.sink.all()[0].severity, Severity::Warning);
  EXPECT_EQ(r.texts(), (Texts{"A", "2"}));
}

TEST(HlslPreprocessor, CallerDefines) {
  PreprocessOptions options;
  options.defines = {{"FOO", ""}, {"BAR", "2"}, {"SQ(x)", "((x)*(x))"}};
  const Result r = run("FOO BAR SQ(3)\n#ifdef FOO\nyes\n#endif", options);
  EXPECT_EQ(r.texts(), (Texts{"2", "(", "(", "3", ")", "*", "(", "3", ")", ")", "yes"}));
  EXPECT_TRUE(r.sink.all().empty());
}

TEST(HlslPreprocessor, MacroDefinitionErrors) {
  const Result r = run("#define F(x x\n#define G(x) #y\n#define H ## a\n#define\n#define 3 x\nok");
  EXPECT_EQ(r.diagnostics(), (Codes{"X1500@1:13", "X1563@2:14", "X1563@3:11", "X1500@4:2", "X1500@5:9"}));
  EXPECT_EQ(r.texts(), (Texts{"ok"}));
}

TEST(HlslPreprocessor, MacroCallErrors) {
  const Result r = run("#define F(x, y) x\nF(1)\n#define G(x) x\nG(1, 2) after\nG(1, 2");
  EXPECT_EQ(r.diagnostics(), (Codes{"X1558@2:1", "X1558@4:1", "X1557@5:1"}));
  EXPECT_EQ(r.texts(), (Texts{"after"}));
}

TEST(HlslPreprocessor, ExpansionBlowUpIsAnErrorNotAHang) {
  std::string source = "#define A0 x x\n";
  for (int i = 1; i <= 40; ++i) source += "#define A" + std::to_string(i) + " A" + std::to_string(i - 1) + " A" + std::to_string(i - 1) + "\n";
  source += "A40\n";
  const Result r = run(source);
  EXPECT_EQ(r.diagnostics(), (Codes{"X1561@42:1"}));
  EXPECT_EQ(r.tokens.back().kind, TokenKind::EndOfFile);
}

TEST(HlslPreprocessor, DeeplyNestedArgumentsAreAnErrorNotACrash) {
  std::string source = "#define F(x) x\n";
  for (int i = 0; i < 5000; ++i) source += "F(";
  source += "1";
  for (int i = 0; i < 5000; ++i) source += ")";
  const Result r = run(source);
  // Reported at the 201st F (column 401), where the nesting passes 200.
  EXPECT_EQ(r.diagnostics(), (Codes{"X1561@2:401"}));
}

// ---- conditionals ----------------------------------------------------------------

// "yes" or "no": which group of `#if expr` the preprocessor reads.
std::string branch(const std::string& expr, const PreprocessOptions& options = {}) {
  const Result r = run("#if " + expr + "\nyes\n#else\nno\n#endif\n", options);
  EXPECT_TRUE(r.sink.all().empty()) << expr << ": " << (r.sink.all().empty() ? "" : r.sink.all()[0].str());
  return r.texts().size() == 1 ? r.texts()[0] : "?";
}

TEST(HlslPreprocessor, IfArithmetic) {
  EXPECT_EQ(branch("1 + 2 * 3 == 7"), "yes");
  EXPECT_EQ(branch("(1 + 2) * 3 == 9"), "yes");
  EXPECT_EQ(branch("10 / 3 == 3 && 10 % 3 == 1"), "yes");
  EXPECT_EQ(branch("-7 / 2 == -3"), "yes");  // division truncates toward zero
  EXPECT_EQ(branch("10 - 2 - 3 == 5"), "yes");
  EXPECT_EQ(branch("1 << 4 == 16 && 256 >> 4 == 16"), "yes");
  EXPECT_EQ(branch("-1 < 0"), "yes");
  EXPECT_EQ(branch("-1 < 0u"), "no");  // compared as unsigned
  EXPECT_EQ(branch("0xff == 255 && 017 == 15 && 10L == 10"), "yes");
  EXPECT_EQ(branch("(5 & 3) == 1 && (5 | 3) == 7 && (5 ^ 3) == 6"), "yes");
  EXPECT_EQ(branch("~0 == -1 && !0 && !!7 && -(-3) == +3"), "yes");
  EXPECT_EQ(branch("3 > 2 > 1"), "no");  // (3 > 2) is 1, and 1 > 1 is false
  EXPECT_EQ(branch("2 >= 2 && 2 <= 2 && 2 != 3"), "yes");
  EXPECT_EQ(branch("1 ? 2 : 0"), "yes");
  EXPECT_EQ(branch("0 ? 1 : 0"), "no");
  EXPECT_EQ(branch("0 ? 1 : 1 ? 0 : 1"), "no");
  EXPECT_EQ(branch("0 || 0"), "no");
  EXPECT_EQ(branch("0 && 1 / 0"), "no");  // not evaluated: no error
  EXPECT_EQ(branch("1 || 1 / 0"), "yes");
  EXPECT_EQ(branch("1 ? 1 : 1 % 0"), "yes");
  EXPECT_EQ(branch("UNDEFINED_NAME == 0 && !UNDEFINED_NAME"), "yes");
}

TEST(HlslPreprocessor, IfWithMacrosAndDefined) {
  PreprocessOptions options;
  options.defines = {{"FOO", ""}, {"V", "3"}, {"TWICE(x)", "((x) * 2)"}};
  EXPECT_EQ(branch("defined(FOO) && defined V && !defined NOPE && !defined(NOPE)", options), "yes");
  EXPECT_EQ(branch("V * 2 == 6 && TWICE(V) == 6", options), "yes");
  EXPECT_EQ(branch("defined NOPE", options), "no");
}

TEST(HlslPreprocessor, DivisionByZeroIsAnError) {
  const Result r = run("#if 1 / 0\na\n#elif 1 % (2 - 2)\nb\n#else\nc\n#endif");
  EXPECT_EQ(r.diagnostics(), (Codes{"X1560@1:7", "X1560@3:9"}));
  EXPECT_EQ(r.texts(), (Texts{"c"}));  // a failed condition counts as false
}

TEST(HlslPreprocessor, BadIfExpressions) {
  const Result r = run("#if\n#endif\n#if 1 +\n#endif\n#if (1\n#endif\n#if 1.5\n#endif\n#if 1 2\n#endif\n#if defined(\n#endif\n#if 09\n#endif");
  EXPECT_EQ(r.diagnostics(), (Codes{"X1559@1:2", "X1559@3:2", "X1559@5:2", "X1559@7:5", "X1559@9:7",
                                    "X1500@11:5", "X1559@13:5"}));
}

TEST(HlslPreprocessor, DeeplyNestedIfExpressionIsAnError) {
  const Result r = run("#if " + std::string(100000, '(') + "1" + std::string(100000, ')') + "\n#endif\n#if " +
                       std::string(100000, '~') + "1\n#endif\n");
  ASSERT_EQ(r.sink.all().size(), 2u);
  EXPECT_EQ(r.sink.all()[0].code, "X1559");
  EXPECT_EQ(r.sink.all()[1].code, "X1559");
}

TEST(HlslPreprocessor, ElifChains) {
  const Result r = run(
      "#define V 2\n"
      "#if V == 1\none\n#elif V == 2\ntwo\n#elif V == 2\nagain\n#else\nother\n#endif\n"
      "#if 0\n#if 1\na\n#else\nb\n#endif\nc\n#elif 0\nd\n#else\ne\n#endif\n"
      "#ifdef V\nf\n#endif\n#ifndef V\ng\n#elif 1\nh\n#endif\n#ifndef W\ni\n#endif");
  EXPECT_EQ(r.texts(), (Texts{"two", "e", "f", "h", "i"}));
  EXPECT_TRUE(r.sink.all().empty());
  ASSERT_EQ(r.tokens.size(), 6u);
  expectToken(r.tokens[0], TokenKind::Identifier, "two", 5, 1);
  expectToken(r.tokens[1], TokenKind::Identifier, "e", 21, 1);
}

TEST(HlslPreprocessor, SkippedGroupsMayHoldAnything) {
  const Result r = run("#if 0\ndon't \"care @\n#unknown directive\n#if 1/0\n#endif\n#endif\nx");
  EXPECT_EQ(r.texts(), (Texts{"x"}));
  EXPECT_TRUE(r.sink.all().empty());
}

TEST(HlslPreprocessor, ConditionalStructureErrors) {
  const Result r = run("#else\n#if 0\n#else\n#else\n#endif\n#endif\n  #elif 1\n#if 1\nx\n#ifdef Y\n");
  EXPECT_EQ(r.diagnostics(), (Codes{"X1554@1:1", "X1556@4:1", "X1554@6:1", "X1554@7:3", "X1555@8:1", "X1555@10:1"}));
  EXPECT_EQ(r.texts(), (Texts{"x"}));
}

// ---- other directives ------------------------------------------------------------

TEST(HlslPreprocessor, ErrorDirective) {
  const Result r = run("#error  bad thing here\nint x;\n  #  error second");
  EXPECT_EQ(r.diagnostics(), (Codes{"X1550@1:1", "X1550@3:3"}));
  EXPECT_EQ(r.sink.all()[0].message, "#error bad thing here");
  EXPECT_EQ(r.texts(), (Texts{"int", "x", ";"}));
}

TEST(HlslPreprocessor, LineDirective) {
  const Result r = run("a\n#line 100\nb\n#line 7 \"other.hlsl\"\nc __LINE__ __FILE__\n@");
  ASSERT_EQ(r.tokens.size(), 6u);
  expectToken(r.tokens[0], TokenKind::Identifier, "a", 1, 1);
  expectToken(r.tokens[1], TokenKind::Identifier, "b", 100, 1);
  expectToken(r.tokens[2], TokenKind::Identifier, "c", 7, 1);
  expectToken(r.tokens[3], TokenKind::IntLiteral, "7", 7, 3);
  expectToken(r.tokens[4], TokenKind::StringLiteral, "other.hlsl", 7, 12);
  EXPECT_EQ(r.tokens[1].file, "t.hlsl");
  EXPECT_EQ(r.tokens[2].file, "other.hlsl");
  ASSERT_EQ(r.sink.all().size(), 1u);  // diagnostics follow #line too
  EXPECT_EQ(r.sink.all()[0].where.file, "other.hlsl");
  EXPECT_EQ(r.diagnostics(), (Codes{"X1553@8:1"}));
}

TEST(HlslPreprocessor, PragmasBecomeTokens) {
  const Result r = run("#pragma pack_matrix(row_major)\n  #  pragma   warning( disable : 3206 )  \nfloat x;\n#pragma something else");
  ASSERT_EQ(r.tokens.size(), 7u);
  expectToken(r.tokens[0], TokenKind::Pragma, "pack_matrix(row_major)", 1, 1);
  expectToken(r.tokens[1], TokenKind::Pragma, "warning( disable : 3206 )", 2, 3);
  expectToken(r.tokens[2], TokenKind::Identifier, "float", 3, 1);
  expectToken(r.tokens[5], TokenKind::Pragma, "something else", 4, 1);
  EXPECT_TRUE(r.sink.all().empty());
}

TEST(HlslPreprocessor, NullDirectiveAndDirectiveContinuation) {
  const Result r = run("#\n# \n#define X 1 + \\\n  2\nX");
  ASSERT_EQ(r.tokens.size(), 4u);
  expectToken(r.tokens[0], TokenKind::IntLiteral, "1", 5, 1);
  expectToken(r.tokens[2], TokenKind::IntLiteral, "2", 5, 1);
  EXPECT_TRUE(r.sink.all().empty());
}

TEST(HlslPreprocessor, CommentInsideDirectiveSpansLines) {
  // A block comment is one space: the #define goes on after it.
  const Result r = run("#define X 1 /* two\nlines */ + 2\nX");
  EXPECT_EQ(r.texts(), (Texts{"1", "+", "2"}));
}

TEST(HlslPreprocessor, HashNotAtLineStartIsAToken) {
  const Result r = run("a # b");
  EXPECT_EQ(r.texts(), (Texts{"a", "#", "b"}));
  EXPECT_TRUE(r.sink.all().empty());
}

TEST(HlslPreprocessor, ErrorRecoveryReportsEveryProblem) {
  const Result r = run("#foo\nint a;\n#else\n#define\n#if 1 / 0\n#endif\n#endif\nint b;");
  EXPECT_EQ(r.diagnostics(), (Codes{"X1504@1:2", "X1554@3:1", "X1500@4:2", "X1560@5:7", "X1554@7:1"}));
  EXPECT_EQ(r.texts(), (Texts{"int", "a", ";", "int", "b", ";"}));
}

TEST(HlslPreprocessor, ExtraTokensWarn) {
  const Result r = run("#ifndef A B\n#endif C\n");
  EXPECT_EQ(r.diagnostics(), (Codes{"X1567@1:11", "X1567@2:8"}));
  EXPECT_EQ(r.sink.errorCount(), 0);
}

// ---- #include --------------------------------------------------------------------

TEST(HlslPreprocessor, IncludeSearchesTheIncluderFirstThenTheDirectories) {
  PreprocessOptions options;
  options.includeDirs = {kIncludeDir + "/dirs"};
  const Result r = run("#include \"local.h\"\n#include \"sub/deep.h\"\n#include <only_in_dir.h>\n#include \"only_in_dir.h\"\nint end;",
                       options, kIncludeDir + "/main.hlsl");
  EXPECT_TRUE(r.sink.all().empty()) << (r.sink.all().empty() ? "" : r.sink.all()[0].str());
  EXPECT_EQ(r.texts(), (Texts{"int", "local", ";", "int", "sibling", ";", "int", "deep", ";", "int", "fromDir", ";",
                              "int", "fromDir", ";", "int", "end", ";"}));
  ASSERT_EQ(r.tokens.size(), 19u);
  expectToken(r.tokens[1], TokenKind::Identifier, "local", 1, 5);
  EXPECT_EQ(r.tokens[1].file, kIncludeDir + "/local.h");
  EXPECT_EQ(r.tokens[4].file, kIncludeDir + "/sub/sibling.h");  // found next to deep.h
  expectToken(r.tokens[7], TokenKind::Identifier, "deep", 2, 5);
  EXPECT_EQ(r.tokens[7].file, kIncludeDir + "/sub/deep.h");
  EXPECT_EQ(r.tokens[10].file, kIncludeDir + "/dirs/only_in_dir.h");
  expectToken(r.tokens[16], TokenKind::Identifier, "end", 5, 5);
  EXPECT_EQ(r.tokens[16].file, kIncludeDir + "/main.hlsl");
}

TEST(HlslPreprocessor, IncludedMacrosAndLines) {
  const Result r = run("#include \"macros.h\"\nint x = FROM_HEADER + __LINE__;", {}, kIncludeDir + "/main.hlsl");
  EXPECT_EQ(r.texts(), (Texts{"int", "header", "=", "2", "+", "5", ";", "int", "x", "=", "5", "+", "2", ";"}));
  EXPECT_EQ(r.tokens[3].file, kIncludeDir + "/macros.h");
}

TEST(HlslPreprocessor, AngledIncludeDoesNotSearchTheIncluder) {
  const Result r = run("#include <local.h>\n#include \"nope.h\"\n#include\n#include NAME\n#include \"open", {},
                       kIncludeDir + "/main.hlsl");
  EXPECT_EQ(r.diagnostics(), (Codes{"X1507@1:10", "X1507@2:10", "X1500@3:2", "X1500@4:10", "X1500@5:10"}));
}

TEST(HlslPreprocessor, IncludeCycleIsAnError) {
  const Result r = run("#include \"cycle_a.h\"\nafter", {}, kIncludeDir + "/main.hlsl");
  EXPECT_EQ(r.diagnostics(), (Codes{"X1506@1:1"}));
  EXPECT_EQ(r.sink.all()[0].where.file, kIncludeDir + "/cycle_b.h");
  EXPECT_EQ(r.texts(), (Texts{"after"}));
}

TEST(HlslPreprocessor, OnlyRegularFilesAreIncluded) {
  const Result r = run("#include \"/dev/zero\"\n#include \"sub\"\nx", {}, kIncludeDir + "/main.hlsl");
  EXPECT_EQ(r.diagnostics(), (Codes{"X1565@1:10", "X1565@2:10"}));
  EXPECT_EQ(r.texts(), (Texts{"x"}));
}

TEST(HlslPreprocessor, PragmaOnce) {
  const Result r = run("#include \"once.h\"\n#include \"once.h\"", {}, kIncludeDir + "/main.hlsl");
  EXPECT_EQ(r.texts(), (Texts{"int", "once", ";"}));
  EXPECT_TRUE(r.sink.all().empty());
}

// ---- a large input -----------------------------------------------------------------

// (Speed is measured by benchmarks, not asserted here.)
TEST(HlslPreprocessor, TwoThousandLinesExpandEveryMacro) {
  std::string source = "#define MUL(a, b) ((a) * (b))\n#define LIGHT_COUNT 4\n";
  for (int i = 0; i < 2000; ++i)
    source += "float4 v" + std::to_string(i) + " = MUL(tex2D(s, uv.xy), float4(1.0, 0.5f, 2, LIGHT_COUNT)); // c\n";
  const Result r = run(source);
  // Per line: float4 vN = ( ( tex2D ( s , uv . xy ) ) * ( float4 ( 1.0 , 0.5f , 2 , 4 ) ) ) ; = 29 tokens.
  EXPECT_EQ(r.tokens.size(), 2000u * 29 + 1);
}

}  // namespace
