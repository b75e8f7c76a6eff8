/*
 * The one place that includes the GL headers. Every GL entry point mvr calls is
 * loaded per context into an mvr_gl_api table through the provider's
 * get-proc-address (eglGetProcAddress, OSMesaGetProcAddress, or the
 * application's own), so the library never links libGLESv2 / libGL, works on
 * any provider, and two contexts never share a function pointer table.
 * GL_GLES_PROTOTYPES is 0: calling a gl* function directly does not compile.
 */
#ifndef MVR_GL_API_H
#define MVR_GL_API_H

#define GL_GLES_PROTOTYPES 0
#include <GLES3/gl32.h>
#include <GLES2/gl2ext.h>

#include <stdbool.h>

/* Desktop GL enums the ES headers lack (desktop core profile only). */
#ifndef GL_TEXTURE_CUBE_MAP_SEAMLESS
#define GL_TEXTURE_CUBE_MAP_SEAMLESS 0x884F
#endif
#ifndef GL_NUM_PROGRAM_BINARY_FORMATS
#define GL_NUM_PROGRAM_BINARY_FORMATS 0x87FE
#endif

/* Core GLES 3.0 entry points (also core in desktop GL 4.3): all must resolve.
 * X(pfn type, member) loads "gl" #member. */
#define MVR_GL_CORE_FUNCS(X) \
    X(PFNGLGETSTRINGPROC, GetString) \
    X(PFNGLGETSTRINGIPROC, GetStringi) \
    X(PFNGLGETINTEGERVPROC, GetIntegerv) \
    X(PFNGLGETINTEGERI_VPROC, GetIntegeri_v) \
    X(PFNGLGETINTEGER64VPROC, GetInteger64v) \
    X(PFNGLGETFLOATVPROC, GetFloatv) \
    X(PFNGLGETERRORPROC, GetError) \
    X(PFNGLENABLEPROC, Enable) \
    X(PFNGLDISABLEPROC, Disable) \
    X(PFNGLVIEWPORTPROC, Viewport) \
    X(PFNGLSCISSORPROC, Scissor) \
    X(PFNGLCLEARPROC, Clear) \
    X(PFNGLCLEARCOLORPROC, ClearColor) \
    X(PFNGLCLEARDEPTHFPROC, ClearDepthf) \
    X(PFNGLCLEARBUFFERFVPROC, ClearBufferfv) \
    X(PFNGLCLEARBUFFERFIPROC, ClearBufferfi) \
    X(PFNGLCLEARBUFFERUIVPROC, ClearBufferuiv) \
    X(PFNGLDEPTHFUNCPROC, DepthFunc) \
    X(PFNGLDEPTHMASKPROC, DepthMask) \
    X(PFNGLCOLORMASKPROC, ColorMask) \
    X(PFNGLCULLFACEPROC, CullFace) \
    X(PFNGLFRONTFACEPROC, FrontFace) \
    X(PFNGLBLENDFUNCSEPARATEPROC, BlendFuncSeparate) \
    X(PFNGLBLENDEQUATIONSEPARATEPROC, BlendEquationSeparate) \
    X(PFNGLPOLYGONOFFSETPROC, PolygonOffset) \
    X(PFNGLPIXELSTOREIPROC, PixelStorei) \
    X(PFNGLREADPIXELSPROC, ReadPixels) \
    X(PFNGLREADBUFFERPROC, ReadBuffer) \
    X(PFNGLDRAWBUFFERSPROC, DrawBuffers) \
    X(PFNGLFINISHPROC, Finish) \
    X(PFNGLFLUSHPROC, Flush) \
    X(PFNGLTRANSFORMFEEDBACKVARYINGSPROC, TransformFeedbackVaryings) \
    X(PFNGLBEGINTRANSFORMFEEDBACKPROC, BeginTransformFeedback) \
    X(PFNGLENDTRANSFORMFEEDBACKPROC, EndTransformFeedback) \
    X(PFNGLUNIFORM4IVPROC, Uniform4iv) \
    X(PFNGLGENBUFFERSPROC, GenBuffers) \
    X(PFNGLDELETEBUFFERSPROC, DeleteBuffers) \
    X(PFNGLBINDBUFFERPROC, BindBuffer) \
    X(PFNGLBUFFERDATAPROC, BufferData) \
    X(PFNGLBUFFERSUBDATAPROC, BufferSubData) \
    X(PFNGLBINDBUFFERRANGEPROC, BindBufferRange) \
    X(PFNGLBINDBUFFERBASEPROC, BindBufferBase) \
    X(PFNGLMAPBUFFERRANGEPROC, MapBufferRange) \
    X(PFNGLUNMAPBUFFERPROC, UnmapBuffer) \
    X(PFNGLGENTEXTURESPROC, GenTextures) \
    X(PFNGLDELETETEXTURESPROC, DeleteTextures) \
    X(PFNGLBINDTEXTUREPROC, BindTexture) \
    X(PFNGLACTIVETEXTUREPROC, ActiveTexture) \
    X(PFNGLTEXSTORAGE2DPROC, TexStorage2D) \
    X(PFNGLTEXSTORAGE3DPROC, TexStorage3D) \
    X(PFNGLTEXSUBIMAGE2DPROC, TexSubImage2D) \
    X(PFNGLTEXSUBIMAGE3DPROC, TexSubImage3D) \
    X(PFNGLCOMPRESSEDTEXSUBIMAGE2DPROC, CompressedTexSubImage2D) \
    X(PFNGLCOMPRESSEDTEXSUBIMAGE3DPROC, CompressedTexSubImage3D) \
    X(PFNGLTEXPARAMETERIPROC, TexParameteri) \
    X(PFNGLTEXPARAMETERFPROC, TexParameterf) \
    X(PFNGLGENERATEMIPMAPPROC, GenerateMipmap) \
    X(PFNGLGENSAMPLERSPROC, GenSamplers) \
    X(PFNGLDELETESAMPLERSPROC, DeleteSamplers) \
    X(PFNGLBINDSAMPLERPROC, BindSampler) \
    X(PFNGLSAMPLERPARAMETERIPROC, SamplerParameteri) \
    X(PFNGLSAMPLERPARAMETERFPROC, SamplerParameterf) \
    X(PFNGLGENFRAMEBUFFERSPROC, GenFramebuffers) \
    X(PFNGLDELETEFRAMEBUFFERSPROC, DeleteFramebuffers) \
    X(PFNGLBINDFRAMEBUFFERPROC, BindFramebuffer) \
    X(PFNGLFRAMEBUFFERTEXTURE2DPROC, FramebufferTexture2D) \
    X(PFNGLFRAMEBUFFERTEXTURELAYERPROC, FramebufferTextureLayer) \
    X(PFNGLFRAMEBUFFERRENDERBUFFERPROC, FramebufferRenderbuffer) \
    X(PFNGLCHECKFRAMEBUFFERSTATUSPROC, CheckFramebufferStatus) \
    X(PFNGLBLITFRAMEBUFFERPROC, BlitFramebuffer) \
    X(PFNGLINVALIDATEFRAMEBUFFERPROC, InvalidateFramebuffer) \
    X(PFNGLGENRENDERBUFFERSPROC, GenRenderbuffers) \
    X(PFNGLDELETERENDERBUFFERSPROC, DeleteRenderbuffers) \
    X(PFNGLBINDRENDERBUFFERPROC, BindRenderbuffer) \
    X(PFNGLRENDERBUFFERSTORAGEMULTISAMPLEPROC, RenderbufferStorageMultisample) \
    X(PFNGLGETINTERNALFORMATIVPROC, GetInternalformativ) \
    X(PFNGLCREATESHADERPROC, CreateShader) \
    X(PFNGLSHADERSOURCEPROC, ShaderSource) \
    X(PFNGLCOMPILESHADERPROC, CompileShader) \
    X(PFNGLGETSHADERIVPROC, GetShaderiv) \
    X(PFNGLGETSHADERINFOLOGPROC, GetShaderInfoLog) \
    X(PFNGLGETSHADERPRECISIONFORMATPROC, GetShaderPrecisionFormat) \
    X(PFNGLDELETESHADERPROC, DeleteShader) \
    X(PFNGLCREATEPROGRAMPROC, CreateProgram) \
    X(PFNGLATTACHSHADERPROC, AttachShader) \
    X(PFNGLDETACHSHADERPROC, DetachShader) \
    X(PFNGLLINKPROGRAMPROC, LinkProgram) \
    X(PFNGLGETPROGRAMIVPROC, GetProgramiv) \
    X(PFNGLGETPROGRAMINFOLOGPROC, GetProgramInfoLog) \
    X(PFNGLDELETEPROGRAMPROC, DeleteProgram) \
    X(PFNGLUSEPROGRAMPROC, UseProgram) \
    X(PFNGLGETUNIFORMLOCATIONPROC, GetUniformLocation) \
    X(PFNGLGETUNIFORMBLOCKINDEXPROC, GetUniformBlockIndex) \
    X(PFNGLGETACTIVEUNIFORMBLOCKIVPROC, GetActiveUniformBlockiv) \
    X(PFNGLUNIFORMBLOCKBINDINGPROC, UniformBlockBinding) \
    X(PFNGLUNIFORM1IPROC, Uniform1i) \
    X(PFNGLUNIFORM1FPROC, Uniform1f) \
    X(PFNGLUNIFORM1FVPROC, Uniform1fv) \
    X(PFNGLUNIFORM2FPROC, Uniform2f) \
    X(PFNGLUNIFORM3FVPROC, Uniform3fv) \
    X(PFNGLUNIFORM4FVPROC, Uniform4fv) \
    X(PFNGLUNIFORMMATRIX3FVPROC, UniformMatrix3fv) \
    X(PFNGLUNIFORMMATRIX4FVPROC, UniformMatrix4fv) \
    X(PFNGLGETPROGRAMBINARYPROC, GetProgramBinary) \
    X(PFNGLPROGRAMBINARYPROC, ProgramBinary) \
    X(PFNGLPROGRAMPARAMETERIPROC, ProgramParameteri) \
    X(PFNGLGENVERTEXARRAYSPROC, GenVertexArrays) \
    X(PFNGLDELETEVERTEXARRAYSPROC, DeleteVertexArrays) \
    X(PFNGLBINDVERTEXARRAYPROC, BindVertexArray) \
    X(PFNGLVERTEXATTRIBPOINTERPROC, VertexAttribPointer) \
    X(PFNGLVERTEXATTRIBIPOINTERPROC, VertexAttribIPointer) \
    X(PFNGLENABLEVERTEXATTRIBARRAYPROC, EnableVertexAttribArray) \
    X(PFNGLDISABLEVERTEXATTRIBARRAYPROC, DisableVertexAttribArray) \
    X(PFNGLVERTEXATTRIB4FPROC, VertexAttrib4f) \
    X(PFNGLVERTEXATTRIBDIVISORPROC, VertexAttribDivisor) \
    X(PFNGLDRAWARRAYSPROC, DrawArrays) \
    X(PFNGLDRAWELEMENTSPROC, DrawElements) \
    X(PFNGLDRAWARRAYSINSTANCEDPROC, DrawArraysInstanced) \
    X(PFNGLDRAWELEMENTSINSTANCEDPROC, DrawElementsInstanced) \
    X(PFNGLGENQUERIESPROC, GenQueries) \
    X(PFNGLDELETEQUERIESPROC, DeleteQueries) \
    X(PFNGLBEGINQUERYPROC, BeginQuery) \
    X(PFNGLENDQUERYPROC, EndQuery) \
    X(PFNGLGETQUERYOBJECTUIVPROC, GetQueryObjectuiv) \
    X(PFNGLGETQUERYIVPROC, GetQueryiv) \
    X(PFNGLFENCESYNCPROC, FenceSync) \
    X(PFNGLCLIENTWAITSYNCPROC, ClientWaitSync) \
    X(PFNGLDELETESYNCPROC, DeleteSync)

/* Optional entry points: X(pfn type, member, "es_name\0desktop_name\0"). On
 * GLES the first name is tried first, on desktop GL the second: glvnd's
 * eglGetProcAddress returns a dispatch stub for any gl* name, so the name of
 * the other API could "resolve" to a function the driver does not have.
 * An extension only counts in mvr_caps when it is advertised (or core) AND all
 * its entry points resolved. */
#define MVR_GL_OPTIONAL_FUNCS(X) \
    X(PFNGLFRAMEBUFFERTEXTUREMULTIVIEWOVRPROC, FramebufferTextureMultiviewOVR, \
      "glFramebufferTextureMultiviewOVR\0") \
    X(PFNGLFRAMEBUFFERTEXTUREMULTISAMPLEMULTIVIEWOVRPROC, FramebufferTextureMultisampleMultiviewOVR, \
      "glFramebufferTextureMultisampleMultiviewOVR\0") \
    X(PFNGLCLIPCONTROLEXTPROC, ClipControl, "glClipControlEXT\0glClipControl\0") \
    X(PFNGLQUERYCOUNTEREXTPROC, QueryCounter, "glQueryCounterEXT\0glQueryCounter\0") \
    X(PFNGLGETQUERYOBJECTUI64VEXTPROC, GetQueryObjectui64v, \
      "glGetQueryObjectui64vEXT\0glGetQueryObjectui64v\0") \
    X(PFNGLDEBUGMESSAGECALLBACKKHRPROC, DebugMessageCallback, \
      "glDebugMessageCallbackKHR\0glDebugMessageCallback\0") \
    X(PFNGLDEBUGMESSAGECONTROLKHRPROC, DebugMessageControl, \
      "glDebugMessageControlKHR\0glDebugMessageControl\0") \
    X(PFNGLOBJECTLABELKHRPROC, ObjectLabel, "glObjectLabelKHR\0glObjectLabel\0") \
    X(PFNGLPUSHDEBUGGROUPKHRPROC, PushDebugGroup, "glPushDebugGroupKHR\0glPushDebugGroup\0") \
    X(PFNGLPOPDEBUGGROUPKHRPROC, PopDebugGroup, "glPopDebugGroupKHR\0glPopDebugGroup\0") \
    X(PFNGLTEXSTORAGE3DMULTISAMPLEPROC, TexStorage3DMultisample, "glTexStorage3DMultisample\0")

#define MVR_GL_DECLARE_CORE(type, name) type name;
#define MVR_GL_DECLARE_OPTIONAL(type, name, names) type name;

typedef struct mvr_gl_api_table {
    MVR_GL_CORE_FUNCS(MVR_GL_DECLARE_CORE)
    MVR_GL_OPTIONAL_FUNCS(MVR_GL_DECLARE_OPTIONAL)
} mvr_gl_api_table;

typedef void *(*mvr_gl_loader_fn)(const char *name, void *user_data);

/* Loads every entry point. Returns false and names the first missing core
 * function in missing[missing_size]; optional ones are left NULL. */
bool mvr_gl_api_load(mvr_gl_api_table *gl, mvr_gl_loader_fn load, void *user_data,
                     bool desktop, char *missing, size_t missing_size);

/* Reads and drops pending GL errors (after a probe that may fail, or before
 * one, so an application's errors are not taken for ours). Bounded: a lost
 * context may report an error on every call. */
static inline void mvr_gl_clear_errors(const mvr_gl_api_table *gl)
{
    for (int i = 0; i < 16 && gl->GetError() != GL_NO_ERROR; ++i) {
    }
}

#endif
