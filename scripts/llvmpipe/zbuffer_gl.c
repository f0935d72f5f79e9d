/* zbuffer_gl OBJ WIDTH HEIGHT REPS: Mesa's llvmpipe (OpenGL ES 2 through EGL, no display) draws an
 * OBJ mesh under the camera and lights of ../shared/perf/bunny.toml, flat normals (each face its
 * own three vertices, as rastray's flat-shaded meshes), with the lighting of design.md computed
 * per vertex (Gouraud) and per fragment (Phong). Prints, for each, the median and minimum time of
 * one frame: clear, draw, glFinish. The image stays in llvmpipe's own buffer, as rastray's stays
 * in its frame. Threads: LP_NUM_THREADS (llvmpipe's rasterizer threads). */
#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GLES2/gl2.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static const char *VERTEX_COMMON =
    "uniform mat4 mvp;\n"
    "attribute vec3 pos; attribute vec3 nrm;\n";
static const char *LIGHTING =
    "uniform vec3 eye; uniform vec3 lp[2]; uniform float li[2];\n"
    "vec3 light(vec3 p, vec3 n) {\n"
    "  vec3 color = vec3(0.9, 0.7, 0.5); vec3 v = normalize(eye - p);\n"
    "  if (dot(n, v) < 0.0) n = -n;\n"
    "  vec3 c = 0.1 * color;\n"
    "  for (int i = 0; i < 2; i++) {\n"
    "    vec3 l = normalize(lp[i] - p); float nl = dot(n, l);\n"
    "    if (nl > 0.0) {\n"
    "      vec3 r = reflect(-l, n);\n"
    "      c += li[i] * (0.7 * nl * color + 0.3 * pow(max(dot(r, v), 0.0), 32.0) * vec3(1.0));\n"
    "    }\n"
    "  }\n"
    "  return c;\n"
    "}\n";

static GLuint compile(GLenum kind, const char *a, const char *b, const char *c) {
  GLuint s = glCreateShader(kind);
  const char *parts[3] = {a, b, c};
  glShaderSource(s, 3, parts, NULL);
  glCompileShader(s);
  GLint ok;
  glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[2048];
    glGetShaderInfoLog(s, sizeof log, NULL, log);
    fprintf(stderr, "shader: %s\n", log);
    exit(1);
  }
  return s;
}

static GLuint program(int per_fragment) {
  GLuint p = glCreateProgram();
  if (per_fragment) {
    glAttachShader(p, compile(GL_VERTEX_SHADER, VERTEX_COMMON,
                              "varying vec3 wp; varying vec3 wn;\n",
                              "void main() { wp = pos; wn = nrm; gl_Position = mvp * vec4(pos, 1.0); }\n"));
    glAttachShader(p, compile(GL_FRAGMENT_SHADER, "precision highp float;\nvarying vec3 wp; varying vec3 wn;\n",
                              LIGHTING,
                              "void main() { gl_FragColor = vec4(light(wp, normalize(wn)), 1.0); }\n"));
  } else {
    glAttachShader(p, compile(GL_VERTEX_SHADER, VERTEX_COMMON, LIGHTING,
                              "varying vec3 col;\n"
                              "void main() { col = light(pos, nrm); gl_Position = mvp * vec4(pos, 1.0); }\n"));
    glAttachShader(p, compile(GL_FRAGMENT_SHADER, "precision highp float;\nvarying vec3 col;\n", "",
                              "void main() { gl_FragColor = vec4(col, 1.0); }\n"));
  }
  glBindAttribLocation(p, 0, "pos");
  glBindAttribLocation(p, 1, "nrm");
  glLinkProgram(p);
  return p;
}

/* Reads `v` and `f` lines (polygons fanned into triangles); returns flat-shaded triangles as
 * interleaved position and face normal, 6 floats per vertex. */
static float *load_obj(const char *path, int *triangles) {
  FILE *f = fopen(path, "r");
  if (!f) { perror(path); exit(1); }
  int nv = 0, cap = 1 << 16, tcap = 1 << 16, nt = 0;
  float *v = malloc(sizeof(float) * 3 * cap);
  float *out = malloc(sizeof(float) * 18 * tcap);
  char line[4096];
  while (fgets(line, sizeof line, f)) {
    if (line[0] == 'v' && line[1] == ' ') {
      if (nv == cap) v = realloc(v, sizeof(float) * 3 * (cap *= 2));
      sscanf(line + 2, "%f %f %f", &v[3 * nv], &v[3 * nv + 1], &v[3 * nv + 2]);
      nv++;
    } else if (line[0] == 'f' && line[1] == ' ') {
      int idx[64], n = 0;
      char *s = line + 2, *end;
      while (n < 64) {
        long i = strtol(s, &end, 10);
        if (end == s) break;
        idx[n++] = (int)(i < 0 ? nv + i : i - 1);
        s = end;
        while (*s && *s != ' ' && *s != '\t' && *s != '\n') s++;
      }
      for (int k = 1; k + 1 < n; k++) {
        if (nt == tcap) out = realloc(out, sizeof(float) * 18 * (tcap *= 2));
        const float *a = &v[3 * idx[0]], *b = &v[3 * idx[k]], *c = &v[3 * idx[k + 1]];
        float e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
        float nx = e1[1] * e2[2] - e1[2] * e2[1], ny = e1[2] * e2[0] - e1[0] * e2[2], nz = e1[0] * e2[1] - e1[1] * e2[0];
        float len = sqrtf(nx * nx + ny * ny + nz * nz);
        if (len > 0) { nx /= len; ny /= len; nz /= len; }
        const float *corner[3] = {a, b, c};
        for (int j = 0; j < 3; j++) {
          float *o = &out[18 * nt + 6 * j];
          o[0] = corner[j][0]; o[1] = corner[j][1]; o[2] = corner[j][2];
          o[3] = nx; o[4] = ny; o[5] = nz;
        }
        nt++;
      }
    }
  }
  fclose(f);
  free(v);
  *triangles = nt;
  return out;
}

/* Column-major perspective(fov_y 45°, near 0.01, far 100) × look_at(eye, target, +y). */
static void camera(float *m, float aspect, const float *eye, const float *target) {
  float f[3] = {target[0] - eye[0], target[1] - eye[1], target[2] - eye[2]};
  float fl = sqrtf(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
  for (int i = 0; i < 3; i++) f[i] /= fl;
  float s[3] = {f[1] * 0 - f[2] * 1, f[2] * 0 - f[0] * 0, f[0] * 1 - f[1] * 0};
  float sl = sqrtf(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]);
  for (int i = 0; i < 3; i++) s[i] /= sl;
  float u[3] = {s[1] * f[2] - s[2] * f[1], s[2] * f[0] - s[0] * f[2], s[0] * f[1] - s[1] * f[0]};
  float view[16] = {s[0], u[0], -f[0], 0, s[1], u[1], -f[1], 0, s[2], u[2], -f[2], 0,
                    -(s[0] * eye[0] + s[1] * eye[1] + s[2] * eye[2]),
                    -(u[0] * eye[0] + u[1] * eye[1] + u[2] * eye[2]),
                    f[0] * eye[0] + f[1] * eye[1] + f[2] * eye[2], 1};
  float t = 1.0f / tanf(0.5f * 45.0f * (float)M_PI / 180.0f), n = 0.01f, fa = 100.0f;
  float proj[16] = {t / aspect, 0, 0, 0, 0, t, 0, 0, 0, 0, (fa + n) / (n - fa), -1, 0, 0, 2 * fa * n / (n - fa), 0};
  for (int c = 0; c < 4; c++)
    for (int r = 0; r < 4; r++) {
      float x = 0;
      for (int k = 0; k < 4; k++) x += proj[k * 4 + r] * view[c * 4 + k];
      m[c * 4 + r] = x;
    }
}

static double now_ms(void) {
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return t.tv_sec * 1e3 + t.tv_nsec / 1e6;
}

static int by_value(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

int main(int argc, char **argv) {
  if (argc < 4) { fprintf(stderr, "usage: %s OBJ WIDTH HEIGHT [REPS]\n", argv[0]); return 2; }
  int w = atoi(argv[2]), h = atoi(argv[3]), reps = argc > 4 ? atoi(argv[4]) : 7;
  PFNEGLGETPLATFORMDISPLAYEXTPROC get_display =
      (PFNEGLGETPLATFORMDISPLAYEXTPROC)eglGetProcAddress("eglGetPlatformDisplayEXT");
  EGLDisplay dpy = get_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, NULL);
  if (!eglInitialize(dpy, NULL, NULL)) { fprintf(stderr, "no EGL display\n"); return 1; }
  EGLint cfg_attr[] = {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE, EGL_OPENGL_ES2_BIT,
                       EGL_RED_SIZE, 8, EGL_GREEN_SIZE, 8, EGL_BLUE_SIZE, 8, EGL_DEPTH_SIZE, 24, EGL_NONE};
  EGLConfig cfg;
  EGLint n;
  if (!eglChooseConfig(dpy, cfg_attr, &cfg, 1, &n) || n < 1) { fprintf(stderr, "no EGL config\n"); return 1; }
  EGLint pb_attr[] = {EGL_WIDTH, w, EGL_HEIGHT, h, EGL_NONE};
  EGLSurface surf = eglCreatePbufferSurface(dpy, cfg, pb_attr);
  eglBindAPI(EGL_OPENGL_ES_API);
  EGLint ctx_attr[] = {EGL_CONTEXT_CLIENT_VERSION, 2, EGL_NONE};
  EGLContext ctx = eglCreateContext(dpy, cfg, EGL_NO_CONTEXT, ctx_attr);
  if (!eglMakeCurrent(dpy, surf, surf, ctx)) { fprintf(stderr, "cannot make the context current\n"); return 1; }

  int tris;
  float *mesh = load_obj(argv[1], &tris);
  /* bunny.toml moves the model's centre to its position: the OBJ's own coordinates. */
  GLuint vbo;
  glGenBuffers(1, &vbo);
  glBindBuffer(GL_ARRAY_BUFFER, vbo);
  glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)sizeof(float) * 18 * tris, mesh, GL_STATIC_DRAW);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 24, (void *)0);
  glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, 24, (void *)12);
  glEnableVertexAttribArray(0);
  glEnableVertexAttribArray(1);
  glViewport(0, 0, w, h);
  glEnable(GL_DEPTH_TEST);
  glClearColor(0, 0, 0, 1);

  const float eye[3] = {0.0854165f, 0.189687f, 0.225701f}, target[3] = {-0.0168405f, 0.110154f, -0.001537f};
  const float lp[6] = {-0.267087f, 0.485524f, 0.373833f, 0.358529f, 0.235277f, 0.24871f}, li[2] = {0.8f, 0.4f};
  float mvp[16];
  camera(mvp, (float)w / h, eye, target);
  const char *name[2] = {"Gouraud", "Phong"};
  for (int pf = 0; pf < 2; pf++) {
    GLuint p = program(pf);
    glUseProgram(p);
    glUniformMatrix4fv(glGetUniformLocation(p, "mvp"), 1, GL_FALSE, mvp);
    glUniform3fv(glGetUniformLocation(p, "eye"), 1, eye);
    glUniform3fv(glGetUniformLocation(p, "lp"), 2, lp);
    glUniform1fv(glGetUniformLocation(p, "li"), 2, li);
    double *ms = malloc(sizeof(double) * reps);
    for (int r = -1; r < reps; r++) { /* one untimed frame compiles the shaders */
      double t = now_ms();
      glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
      glDrawArrays(GL_TRIANGLES, 0, 3 * tris);
      glFinish();
      if (r >= 0) ms[r] = now_ms() - t;
    }
    qsort(ms, reps, sizeof(double), by_value);
    unsigned char *px = malloc((size_t)4 * w * h);
    glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, px);
    long covered = 0;
    for (long i = 0; i < (long)w * h; i++) covered += (px[4 * i] | px[4 * i + 1] | px[4 * i + 2]) != 0;
    printf("llvmpipe %s %dx%d %d triangles: median %.2f ms (min %.2f), %ld px covered\n", name[pf], w, h, tris,
           ms[reps / 2], ms[0], covered);
    free(px);
    free(ms);
  }
  printf("renderer: %s\n", (const char *)glGetString(GL_RENDERER));
  return 0;
}
