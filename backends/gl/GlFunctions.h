// Every GL entry point the backend uses, loaded through the chosen platform's GetProcAddress
// (EGL or OSMesa) so one binary runs on either. Hand-written because libepoxy cannot load
// through OSMesaGetProcAddress.
#pragma once
#include <GL/glcorearb.h>

namespace fe::gl {

#define FE_GL_FUNCTIONS(X)                                                       \
    X(PFNGLGETSTRINGPROC, GetString)                                             \
    X(PFNGLGETSTRINGIPROC, GetStringi)                                           \
    X(PFNGLGETINTEGERVPROC, GetIntegerv)                                         \
    X(PFNGLGETFLOATVPROC, GetFloatv)                                             \
    X(PFNGLGETINTEGERI_VPROC, GetIntegeri_v)                                     \
    X(PFNGLGETERRORPROC, GetError)                                               \
    X(PFNGLGETGRAPHICSRESETSTATUSPROC, GetGraphicsResetStatus)                   \
    X(PFNGLENABLEPROC, Enable)                                                   \
    X(PFNGLPATCHPARAMETERIPROC, PatchParameteri)                                 \
    X(PFNGLDISABLEPROC, Disable)                                                 \
    X(PFNGLENABLEIPROC, Enablei)                                                 \
    X(PFNGLPOINTPARAMETERIPROC, PointParameteri)                                 \
    X(PFNGLDISABLEIPROC, Disablei)                                               \
    X(PFNGLCLIPCONTROLPROC, ClipControl)                                         \
    X(PFNGLPROVOKINGVERTEXPROC, ProvokingVertex)                                 \
    X(PFNGLDEBUGMESSAGECALLBACKPROC, DebugMessageCallback)                       \
    X(PFNGLCREATEBUFFERSPROC, CreateBuffers)                                     \
    X(PFNGLNAMEDBUFFERSTORAGEPROC, NamedBufferStorage)                           \
    X(PFNGLNAMEDBUFFERSUBDATAPROC, NamedBufferSubData)                           \
    X(PFNGLGETNAMEDBUFFERSUBDATAPROC, GetNamedBufferSubData)                     \
    X(PFNGLDELETEBUFFERSPROC, DeleteBuffers)                                     \
    X(PFNGLBINDBUFFERPROC, BindBuffer)                                           \
    X(PFNGLCREATETEXTURESPROC, CreateTextures)                                   \
    X(PFNGLTEXTURESTORAGE2DPROC, TextureStorage2D)                               \
    X(PFNGLTEXTURESTORAGE3DPROC, TextureStorage3D)                               \
    X(PFNGLTEXTURESTORAGE2DMULTISAMPLEPROC, TextureStorage2DMultisample)         \
    X(PFNGLTEXTURESUBIMAGE3DPROC, TextureSubImage3D)                             \
    X(PFNGLCOMPRESSEDTEXTURESUBIMAGE2DPROC, CompressedTextureSubImage2D)         \
    X(PFNGLCOMPRESSEDTEXTURESUBIMAGE3DPROC, CompressedTextureSubImage3D)         \
    X(PFNGLGETTEXTURESUBIMAGEPROC, GetTextureSubImage)                           \
    X(PFNGLGENERATETEXTUREMIPMAPPROC, GenerateTextureMipmap)                     \
    X(PFNGLTEXTURESUBIMAGE2DPROC, TextureSubImage2D)                             \
    X(PFNGLGETTEXTUREIMAGEPROC, GetTextureImage)                                 \
    X(PFNGLTEXTUREPARAMETERIPROC, TextureParameteri)                             \
    X(PFNGLDELETETEXTURESPROC, DeleteTextures)                                   \
    X(PFNGLINVALIDATETEXIMAGEPROC, InvalidateTexImage)                           \
    X(PFNGLCREATESAMPLERSPROC, CreateSamplers)                                   \
    X(PFNGLSAMPLERPARAMETERIPROC, SamplerParameteri)                             \
    X(PFNGLSAMPLERPARAMETERFPROC, SamplerParameterf)                             \
    X(PFNGLSAMPLERPARAMETERFVPROC, SamplerParameterfv)                           \
    X(PFNGLCLEARNAMEDBUFFERDATAPROC, ClearNamedBufferData)                       \
    X(PFNGLCLEARTEXIMAGEPROC, ClearTexImage)                                     \
    X(PFNGLSAMPLEMASKIPROC, SampleMaski)                                         \
    X(PFNGLCLEARNAMEDBUFFERSUBDATAPROC, ClearNamedBufferSubData)                 \
    X(PFNGLDEBUGMESSAGEINSERTPROC, DebugMessageInsert)                           \
    X(PFNGLCLEARNAMEDFRAMEBUFFERIVPROC, ClearNamedFramebufferiv)                 \
    X(PFNGLDELETESAMPLERSPROC, DeleteSamplers)                                   \
    X(PFNGLCREATESHADERPROC, CreateShader)                                       \
    X(PFNGLSHADERBINARYPROC, ShaderBinary)                                       \
    X(PFNGLSPECIALIZESHADERPROC, SpecializeShader)                               \
    X(PFNGLGETSHADERIVPROC, GetShaderiv)                                         \
    X(PFNGLGETSHADERINFOLOGPROC, GetShaderInfoLog)                               \
    X(PFNGLDELETESHADERPROC, DeleteShader)                                       \
    X(PFNGLCREATEPROGRAMPROC, CreateProgram)                                     \
    X(PFNGLATTACHSHADERPROC, AttachShader)                                       \
    X(PFNGLLINKPROGRAMPROC, LinkProgram)                                         \
    X(PFNGLGETPROGRAMIVPROC, GetProgramiv)                                       \
    X(PFNGLGETPROGRAMINFOLOGPROC, GetProgramInfoLog)                             \
    X(PFNGLDELETEPROGRAMPROC, DeleteProgram)                                     \
    X(PFNGLUSEPROGRAMPROC, UseProgram)                                           \
    X(PFNGLCREATEVERTEXARRAYSPROC, CreateVertexArrays)                           \
    X(PFNGLVERTEXARRAYATTRIBFORMATPROC, VertexArrayAttribFormat)                 \
    X(PFNGLVERTEXARRAYATTRIBIFORMATPROC, VertexArrayAttribIFormat)               \
    X(PFNGLVERTEXARRAYATTRIBBINDINGPROC, VertexArrayAttribBinding)               \
    X(PFNGLVERTEXARRAYBINDINGDIVISORPROC, VertexArrayBindingDivisor)             \
    X(PFNGLENABLEVERTEXARRAYATTRIBPROC, EnableVertexArrayAttrib)                 \
    X(PFNGLVERTEXARRAYVERTEXBUFFERPROC, VertexArrayVertexBuffer)                 \
    X(PFNGLVERTEXARRAYELEMENTBUFFERPROC, VertexArrayElementBuffer)               \
    X(PFNGLBINDVERTEXARRAYPROC, BindVertexArray)                                 \
    X(PFNGLDELETEVERTEXARRAYSPROC, DeleteVertexArrays)                           \
    X(PFNGLCREATEFRAMEBUFFERSPROC, CreateFramebuffers)                           \
    X(PFNGLNAMEDFRAMEBUFFERTEXTUREPROC, NamedFramebufferTexture)                 \
    X(PFNGLNAMEDFRAMEBUFFERTEXTURELAYERPROC, NamedFramebufferTextureLayer)       \
    X(PFNGLNAMEDFRAMEBUFFERDRAWBUFFERSPROC, NamedFramebufferDrawBuffers)         \
    X(PFNGLCHECKNAMEDFRAMEBUFFERSTATUSPROC, CheckNamedFramebufferStatus)         \
    X(PFNGLBINDFRAMEBUFFERPROC, BindFramebuffer)                                 \
    X(PFNGLDELETEFRAMEBUFFERSPROC, DeleteFramebuffers)                           \
    X(PFNGLCLEARNAMEDFRAMEBUFFERFVPROC, ClearNamedFramebufferfv)                 \
    X(PFNGLCLEARNAMEDFRAMEBUFFERUIVPROC, ClearNamedFramebufferuiv)               \
    X(PFNGLCLEARNAMEDFRAMEBUFFERFIPROC, ClearNamedFramebufferfi)                 \
    X(PFNGLVIEWPORTPROC, Viewport)                                               \
    X(PFNGLVIEWPORTINDEXEDFPROC, ViewportIndexedf)                               \
    X(PFNGLDEPTHRANGEFPROC, DepthRangef)                                         \
    X(PFNGLSCISSORPROC, Scissor)                                                 \
    X(PFNGLCULLFACEPROC, CullFace)                                               \
    X(PFNGLFRONTFACEPROC, FrontFace)                                             \
    X(PFNGLDEPTHFUNCPROC, DepthFunc)                                             \
    X(PFNGLDEPTHMASKPROC, DepthMask)                                             \
    X(PFNGLSTENCILFUNCSEPARATEPROC, StencilFuncSeparate)                         \
    X(PFNGLSTENCILOPSEPARATEPROC, StencilOpSeparate)                             \
    X(PFNGLSTENCILMASKPROC, StencilMask)                                         \
    X(PFNGLBLENDFUNCSEPARATEIPROC, BlendFuncSeparatei)                           \
    X(PFNGLBLENDEQUATIONSEPARATEIPROC, BlendEquationSeparatei)                   \
    X(PFNGLCOLORMASKIPROC, ColorMaski)                                           \
    X(PFNGLBLENDCOLORPROC, BlendColor)                                           \
    X(PFNGLBINDBUFFERRANGEPROC, BindBufferRange)                                 \
    X(PFNGLBINDTEXTUREUNITPROC, BindTextureUnit)                                 \
    X(PFNGLBINDSAMPLERPROC, BindSampler)                                         \
    X(PFNGLBINDIMAGETEXTUREPROC, BindImageTexture)                               \
    X(PFNGLDRAWARRAYSPROC, DrawArrays)                                           \
    X(PFNGLDRAWELEMENTSBASEVERTEXPROC, DrawElementsBaseVertex)                   \
    X(PFNGLDRAWARRAYSINSTANCEDBASEINSTANCEPROC, DrawArraysInstancedBaseInstance) \
    X(PFNGLDRAWELEMENTSINSTANCEDBASEVERTEXBASEINSTANCEPROC,                      \
      DrawElementsInstancedBaseVertexBaseInstance)                               \
    X(PFNGLDISPATCHCOMPUTEPROC, DispatchCompute)                                 \
    X(PFNGLDISPATCHCOMPUTEINDIRECTPROC, DispatchComputeIndirect)                 \
    X(PFNGLMULTIDRAWARRAYSINDIRECTPROC, MultiDrawArraysIndirect)                 \
    X(PFNGLMULTIDRAWELEMENTSINDIRECTPROC, MultiDrawElementsIndirect)             \
    X(PFNGLPOLYGONOFFSETPROC, PolygonOffset)                                     \
    X(PFNGLGETINTERNALFORMATIVPROC, GetInternalformativ)                         \
    X(PFNGLMEMORYBARRIERPROC, MemoryBarrier)                                     \
    X(PFNGLCOPYNAMEDBUFFERSUBDATAPROC, CopyNamedBufferSubData)                   \
    X(PFNGLCOPYIMAGESUBDATAPROC, CopyImageSubData)                               \
    X(PFNGLCREATEQUERIESPROC, CreateQueries)                                     \
    X(PFNGLQUERYCOUNTERPROC, QueryCounter)                                       \
    X(PFNGLGENQUERIESPROC, GenQueries)                                           \
    X(PFNGLGENTEXTURESPROC, GenTextures)                                         \
    X(PFNGLTEXTUREVIEWPROC, TextureView)                                         \
    X(PFNGLPROGRAMBINARYPROC, ProgramBinary)                                     \
    X(PFNGLGETPROGRAMBINARYPROC, GetProgramBinary)                               \
    X(PFNGLPROGRAMPARAMETERIPROC, ProgramParameteri)                             \
    X(PFNGLBEGINQUERYPROC, BeginQuery)                                           \
    X(PFNGLENDQUERYPROC, EndQuery)                                               \
    X(PFNGLGETQUERYBUFFEROBJECTUI64VPROC, GetQueryBufferObjectui64v)             \
    X(PFNGLGETQUERYOBJECTUI64VPROC, GetQueryObjectui64v)                         \
    X(PFNGLGETQUERYOBJECTIVPROC, GetQueryObjectiv)                               \
    X(PFNGLDELETEQUERIESPROC, DeleteQueries)                                     \
    X(PFNGLFENCESYNCPROC, FenceSync)                                             \
    X(PFNGLCLIENTWAITSYNCPROC, ClientWaitSync)                                   \
    X(PFNGLDELETESYNCPROC, DeleteSync)                                           \
    X(PFNGLFLUSHPROC, Flush)                                                     \
    X(PFNGLFINISHPROC, Finish)                                                   \
    X(PFNGLPUSHDEBUGGROUPPROC, PushDebugGroup)                                   \
    X(PFNGLPOPDEBUGGROUPPROC, PopDebugGroup)                                     \
    X(PFNGLOBJECTLABELPROC, ObjectLabel)                                         \
    X(PFNGLPIXELSTOREIPROC, PixelStorei)                                         \
    X(PFNGLBLITNAMEDFRAMEBUFFERPROC, BlitNamedFramebuffer)                       \
    X(PFNGLNAMEDFRAMEBUFFERREADBUFFERPROC, NamedFramebufferReadBuffer)           \
    X(PFNGLREADNPIXELSPROC, ReadnPixels)                                         \
    X(PFNGLMAPNAMEDBUFFERRANGEPROC, MapNamedBufferRange)                         \
    X(PFNGLINVALIDATETEXSUBIMAGEPROC, InvalidateTexSubImage)

struct GlFunctions {
#define FE_GL_DECLARE(type, name) type name = nullptr;
    FE_GL_FUNCTIONS(FE_GL_DECLARE)
#undef FE_GL_DECLARE
    // Extensions beyond 4.5 core: null when the context lacks them (DeviceFeatures says which).
    PFNGLMULTIDRAWARRAYSINDIRECTCOUNTPROC MultiDrawArraysIndirectCount =
        nullptr;  // ARB_indirect_parameters
    PFNGLMULTIDRAWELEMENTSINDIRECTCOUNTPROC MultiDrawElementsIndirectCount =
        nullptr;                                               // ARB_indirect_parameters
    PFNGLPOLYGONOFFSETCLAMPPROC PolygonOffsetClamp = nullptr;  // ARB_polygon_offset_clamp
};

}  // namespace fe::gl
