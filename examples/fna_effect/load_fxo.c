/* What FNA does with a compiled effect, in C: load an fx_2_0 binary (.fxo) with
 * MojoShader's effect parser, list its parameters and techniques, and print the GLSL
 * MojoShader generates for the shaders of one pass.
 *
 *   refx fxc /T fx_2_0 effect.fx /Fo effect.fxo
 *   load_fxo effect.fxo [TECHNIQUE [PASS]]
 *
 * Exit status: 0 success, 1 the file could not be read or MojoShader reported errors,
 * 2 bad arguments. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The effect API is declared only with MOJOSHADER_EFFECT_SUPPORT defined. */
#define MOJOSHADER_EFFECT_SUPPORT
#include <mojoshader.h>
#include <mojoshader_effects.h>

/* The "backend": every shader of the effect is translated to GLSL by MOJOSHADER_parse. */
static void *compile_shader(const char *mainfn, const unsigned char *tokens, const unsigned int size,
                            const MOJOSHADER_swizzle *swiz, const unsigned int swizcount,
                            const MOJOSHADER_samplerMap *smap, const unsigned int smapcount) {
  return (void *)MOJOSHADER_parse(MOJOSHADER_PROFILE_GLSL, mainfn, tokens, size, swiz, swizcount, smap, smapcount,
                                  NULL, NULL, NULL);
}
static void add_ref(void *shader) { (void)shader; }
static void delete_shader(void *shader) { MOJOSHADER_freeParseData((const MOJOSHADER_parseData *)shader); }
static MOJOSHADER_parseData *parse_data(void *shader) { return (MOJOSHADER_parseData *)shader; }
static void bind_shaders(void *v, void *p) { (void)v; (void)p; }
static void bound_shaders(void **v, void **p) { *v = *p = NULL; }
static void map_uniforms(float **vsf, int **vsi, unsigned char **vsb, float **psf, int **psi, unsigned char **psb) {
  *vsf = *psf = NULL;
  *vsi = *psi = NULL;
  *vsb = *psb = NULL;
}
static void unmap_uniforms(void) {}
static const char *last_error(void) { return "MojoShader could not translate a shader"; }

static unsigned char *read_file(const char *path, unsigned int *size) {
  FILE *f = fopen(path, "rb");
  if (!f) return NULL;
  unsigned char *data = NULL;
  size_t n = 0, cap = 0, got;
  do {
    if (n == cap) {
      cap = cap ? cap * 2 : 65536;
      unsigned char *grown = realloc(data, cap);
      if (!grown) { free(data); fclose(f); return NULL; }
      data = grown;
    }
    got = fread(data + n, 1, cap - n, f);
    n += got;
  } while (got > 0);
  fclose(f);
  *size = (unsigned int)n;
  return data;
}

static const char *type_name(MOJOSHADER_symbolType t) {
  static const char *names[] = {"void", "bool", "int", "float", "string", "texture", "texture1D", "texture2D",
                                "texture3D", "textureCUBE", "sampler", "sampler1D", "sampler2D", "sampler3D",
                                "samplerCUBE", "pixelshader", "vertexshader"};
  return (unsigned)t < sizeof names / sizeof names[0] ? names[t] : "?";
}

static void print_shader(const MOJOSHADER_effect *e, const MOJOSHADER_effectState *state, const char *what) {
  const int id = state->value.valuesI[0];
  if (id <= 0 || id >= e->object_count) return;
  const MOJOSHADER_effectShader *sh = &e->objects[id].shader;
  if (sh->is_preshader || !sh->shader) return;
  const MOJOSHADER_parseData *pd = (const MOJOSHADER_parseData *)sh->shader;
  printf("--- %s (%s %d.%d, %d instructions) ---\n", what, pd->shader_type == MOJOSHADER_TYPE_VERTEX ? "vs" : "ps",
         pd->major_ver, pd->minor_ver, pd->instruction_count);
  for (int i = 0; i < pd->error_count; ++i) printf("error: %s\n", pd->errors[i].error);
  if (pd->output) fwrite(pd->output, 1, (size_t)pd->output_len, stdout);
}

int main(int argc, char **argv) {
  if (argc < 2 || argc > 4) {
    fprintf(stderr, "usage: %s EFFECT.fxo [TECHNIQUE [PASS]]\n", argv[0]);
    return 2;
  }
  unsigned int size = 0;
  unsigned char *bytes = read_file(argv[1], &size);
  if (!bytes) {
    fprintf(stderr, "%s: cannot read the file\n", argv[1]);
    return 1;
  }
  MOJOSHADER_effectShaderContext ctx;
  memset(&ctx, 0, sizeof ctx);
  ctx.compileShader = compile_shader;
  ctx.shaderAddRef = add_ref;
  ctx.deleteShader = delete_shader;
  ctx.getParseData = parse_data;
  ctx.bindShaders = bind_shaders;
  ctx.getBoundShaders = bound_shaders;
  ctx.mapUniformBufferMemory = map_uniforms;
  ctx.unmapUniformBufferMemory = unmap_uniforms;
  ctx.getError = last_error;
  MOJOSHADER_effect *e = MOJOSHADER_compileEffect(bytes, size, NULL, 0, NULL, 0, &ctx);
  free(bytes);
  if (!e || e->error_count > 0) {
    for (int i = 0; e && i < e->error_count; ++i) fprintf(stderr, "%s: %s\n", argv[1], e->errors[i].error);
    if (!e) fprintf(stderr, "%s: MojoShader could not load the effect\n", argv[1]);
    return 1;
  }

  printf("parameters: %d\n", e->param_count);
  for (int i = 0; i < e->param_count; ++i) {
    const MOJOSHADER_effectValue *v = &e->params[i].value;
    printf("  %s", type_name(v->type.parameter_type));
    if (v->type.parameter_class == MOJOSHADER_SYMCLASS_VECTOR) printf("%u", v->type.columns);
    if (v->type.parameter_class == MOJOSHADER_SYMCLASS_MATRIX_ROWS ||
        v->type.parameter_class == MOJOSHADER_SYMCLASS_MATRIX_COLUMNS)
      printf("%ux%u", v->type.rows, v->type.columns);
    if (v->type.elements > 1) printf("[%u]", v->type.elements);
    printf(" %s", v->name ? v->name : "");
    if (v->semantic) printf(" : %s", v->semantic);
    printf("\n");
  }
  printf("techniques: %d\n", e->technique_count);
  int chosen = 0;
  for (int t = 0; t < e->technique_count; ++t) {
    const MOJOSHADER_effectTechnique *tech = &e->techniques[t];
    printf("  %s (%u pass%s)\n", tech->name ? tech->name : "", tech->pass_count, tech->pass_count == 1 ? "" : "es");
    if (argc > 2 && tech->name && strcmp(tech->name, argv[2]) == 0) chosen = t;
  }
  if (argc > 2 && (e->technique_count == 0 || !e->techniques[chosen].name ||
                   strcmp(e->techniques[chosen].name, argv[2]) != 0)) {
    fprintf(stderr, "%s: no technique named '%s'\n", argv[1], argv[2]);
    return 2;
  }
  if (e->technique_count == 0) return 0;
  const MOJOSHADER_effectTechnique *tech = &e->techniques[chosen];
  const unsigned pass = argc > 3 ? (unsigned)atoi(argv[3]) : 0;
  if (pass >= tech->pass_count) {
    fprintf(stderr, "%s: technique '%s' has %u passes\n", argv[1], tech->name, tech->pass_count);
    return 2;
  }
  printf("technique %s, pass %u:\n", tech->name ? tech->name : "", pass);
  for (unsigned s = 0; s < tech->passes[pass].state_count; ++s) {
    const MOJOSHADER_effectState *st = &tech->passes[pass].states[s];
    if (st->type == MOJOSHADER_RS_VERTEXSHADER) print_shader(e, st, "vertex shader");
    if (st->type == MOJOSHADER_RS_PIXELSHADER) print_shader(e, st, "pixel shader");
  }
  MOJOSHADER_deleteEffect(e);
  return 0;
}
