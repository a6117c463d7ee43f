// Fools Engine graphics device interface (layers 1-4): the whole device API in one header.
//
// Contents (grep for the heading):
//   Usage / Conventions / Errors and device loss / Threads and recording / Queues / Textures and views /
//   Pipelines and shaders / Per-draw constants and specialization / Queries / Pipeline cache /
//   Captures / Fixed function / Windows
// Each section ends with the conformance cases (tests/conformance, `fe conformance --case NAME`)
// that show it on every backend.
//
// Usage
// -----
//   auto device = fe::gdi::createDevice({.backend = "auto"});     // Backend.h
//   auto vs = device->createShader({.stage = ShaderStage::Vertex, .binary = shaders::find("tri.vert")});
//   auto fs = device->createShader({.stage = ShaderStage::Fragment,        // or GLSL at run time
//                                   .source = {.text = glsl, .name = "tint.frag"}});
//   auto target = device->createTexture({.format = Format::RGBA8, .width = 64, .height = 64,
//                                         .usage = TextureUsage::RenderTarget | TextureUsage::CopySrc});
//   auto pipe = device->createGraphicsPipeline({.vertexShader = vs, .fragmentShader = fs,
//                                               .colorFormats = {Format::RGBA8}});
//   auto cmd = device->createCommandList();
//   cmd->beginRenderPass({.colors = {{.texture = target, .clear = {0, 0, 0, 1}}}});
//   cmd->setPipeline(pipe);
//   cmd->draw(3);
//   cmd->endRenderPass();
//   device->wait(device->submit(*cmd));
//   fe::gdi::Image img = device->readTexture(target);
// On the CPU rasterizers (llvmpipe, lavapipe) call fe::gdi::keepFreedMemory() first (Backend.h):
// they allocate and free large blocks every frame, and a frame costs 13-15 % more when the C
// library hands those back to the kernel.
// Shown by: culling_winding, indexed_instanced_base_vertex, render_to_texture_then_sample, copies.
//
// Conventions
// -----------
// Identical on every backend, so images match pixel for pixel:
//  - Clip space is Vulkan's: y points down in framebuffer space, depth range [0, 1].
//  - Image rows are stored top to bottom; texture coordinate (0,0) is the first texel in memory.
//  - Counter-clockwise in framebuffer coordinates (y down) is FrontFace::CounterClockwise.
//  - Resource bindings are flat slots: `layout(binding = N)` in GLSL, one namespace per pipeline.
//  - Handles are small typed ids; 0 is the null handle. Destroying a null handle is a no-op;
//    destroying one that is not live (destroyed already) is an Error.
//    A handle belongs to the device that made it: given to another device it is refused as
//    "invalid or destroyed" (ids are salted per device; a 12-bit generation, so this catches
//    the mistake with near certainty rather than always).
//  - Data passed to the device is a ByteSpan (bytesOf(x) for a value, array or vector) and its
//    length must be exactly what the call reads: createBuffer's initial data is desc.size bytes,
//    writeTexture's the subresource's textureByteSize.
// Shown by: culling_winding, scissor_viewport_stencil, sampled_quadrants, upload_lengths_checked.
//
// Errors and device loss
// ----------------------
//  - Errors (invalid descriptions, unsupported formats, missing bindings, backend failures)
//    throw fe::gdi::Error with a message saying what was wrong; nothing is silently ignored.
//  - Native API failures are errors, never aborts. Out of memory (VK_ERROR_OUT_OF_DEVICE_MEMORY
//    or _HOST_MEMORY, GL_OUT_OF_MEMORY) is an Error naming the native call and the object, e.g.
//    "gl-egl: glTextureStorage2D failed for texture 'albedo' (1024x1024 RGBA8): GL_OUT_OF_MEMORY";
//    nothing of the failed object is left behind and the device stays usable. A buffer or
//    texture larger than limits.maxAllocationSize is an Error before any native call.
//  - A lost device (VK_ERROR_DEVICE_LOST; a GL context reset, which a robust context reports
//    through glGetGraphicsResetStatus, polled at submit and wait) throws DeviceLostError, and so
//    does every later call that creates, transfers, submits or waits on that device. Recording
//    is not checked, to keep per-draw calls cheap: recording on a lost device is harmless and
//    its submit throws. destroy(), info(), desc() and the other queries keep working, so objects
//    made before the loss are released normally; destructors wait with waitIdleOrLost().
//  - Tests make the N-th native allocation or submission fail: FE_FAULT_ALLOC=N,
//    FE_FAULT_SUBMIT=N, or fault::arm() (fe/gdi/Faults.h).
// Shown by: binding_mismatch_errors, constants_errors, query_errors, upload_lengths_checked
// (and the fault-injection tests, tests/unit/NativeFaultTests.cpp).
//
// Threads and recording
// ---------------------
// Recording is not executing, on every backend: nothing recorded runs before submit, and what
// a command reads is read when it runs. Lists may be recorded on any threads at once:
//   std::vector<std::unique_ptr<CommandList>> lists;  // one per thread, recorded in parallel
//   std::vector<CommandList*> order = {lists[2].get(), lists[0].get(), lists[1].get()};
//   FenceValue f = device->submit(order);             // one submission, in this order
//   auto* bytes = static_cast<uint8_t*>(device->map(uploadRing));  // Upload: persistent pointer
//   if (device->isComplete(f)) { /* read a Readback buffer through map() */ }
// Every Device member may be called from any thread (CommandList's own rules: its section below).
// Shown by: submission_order, unsubmitted_list_has_no_effect, data_read_at_execution,
// record_on_threads, secondary_lists_in_one_pass, reusable_secondary_lists, create_while_recording,
// destroy_while_in_flight, mapped_upload_ring, async_readback, buffer_barrier_compute_to_indirect, subresource_barrier.
//
// Textures and views
// ------------------
//   auto cube = device->createTexture({.dimension = TextureDimension::TextureCube, .format = Format::RGBA16F,
//                                      .width = 256, .height = 256, .depthOrLayers = 6, .mipLevels = 9,
//                                      .usage = TextureUsage::Sampled | TextureUsage::RenderTarget});
//   device->writeTexture(cube, {.mipLevel = 0, .layer = 4}, bytesOf(facePixels));   // +Z face
//   cmd->beginRenderPass({.colors = {{.texture = cube, .layer = 2}}});              // render into +Y
//   ...
//   cmd->generateMips(cube);                                                        // box-filtered chain
//   auto ms = device->createTexture({.width = w, .height = h, .sampleCount = 4, .usage = TextureUsage::RenderTarget});
//   cmd->beginRenderPass({.colors = {{.texture = ms, .store = StoreOp::DontCare, .resolveTexture = resolved}}});
//  - Kinds: Texture2D, Texture2DArray, TextureCube (6 layers), TextureCubeArray (6 per cube,
//    DeviceFeatures::textureCubeArray), Texture3D (depthOrLayers is the depth). GLSL samples each
//    with sampler2D / sampler2DArray / samplerCube / samplerCubeArray / sampler3D, and a storage
//    binding is declared with the same kind (image2DArray, imageCube, image3D: every layer of one mip).
//  - A Subresource is {mipLevel, layer}; layer is the array layer, cube face (layer % 6 of cube
//    layer / 6, in the order +X -X +Y -Y +Z -Z) or the 3D slice within that mip. Uploads,
//    readback, buffer<->texture copies and attachments each address exactly one subresource.
//  - Multisampled textures (sampleCount 2/4/8 as DeviceLimits::colorSampleCounts/depthSampleCounts
//    allow) are single-mip 2D render targets; pipelines drawing into them set
//    MultisampleState::sampleCount to match. A pass resolves them into single-sample textures:
//    colour by averaging, depth by taking sample 0 (see DepthAttachment). With Sampled usage a
//    shader reads single samples (GLSL sampler2DMS, texelFetch(tex, pixel, sample)); copyTexture
//    moves every sample between textures of one sample count; they are not read back or copied
//    to buffers (resolve them first). Attachments whose contents live inside one pass (a resolved multisampled
//    target, a depth buffer read by no later pass) may be TextureUsage::Transient.
//  - Shadow maps: RasterState depth bias and depth clamp; a SamplerDesc with compareEnable makes
//    sampler2DShadow / sampler2DArrayShadow / samplerCubeShadow return 0..1, filtered (PCF) when Linear.
//  - Indirect work: records (DrawIndirectArgs, DrawIndexedIndirectArgs, DispatchIndirectArgs) in
//    BufferUsage::Indirect buffers, which a compute shader may write; *Count forms take the draw
//    count from a buffer (DeviceFeatures::drawIndirectCount). Indexed indirect draws need the
//    index buffer bound at offset 0 (the records' firstIndex offsets it).
//  - Block-compressed formats (BC1/3/4/5/7, sRGB forms) are sampled-only
//    (DeviceFeatures::textureCompressionBC); uploads are rows of 4x4 blocks.
//   auto mip1 = device->createTextureView(chain, {.baseMip = 1, .mipCount = 1});  // bind anywhere
//   device->writeTextureRegion(tex, {.x = 8, .y = 8, .width = 16, .height = 16}, bytes, {.bytesPerRow = 256});
//   cmd->copyTexture(tex, {.mipLevel = 1}, tex, {.width = 32, .height = 32});   // regions, mips, layers
//  - Regions and layouts (TextureRegion, TexelLayout): offsets multiples of 4 and of the texel
//    size, bytesPerRow a multiple of the texel size, compressed data tightly packed. Depth and
//    stencil go to and from buffers one aspect at a time (TextureRegion::aspect), in Vulkan's
//    buffer layouts on every backend (aspectTexelBytes).
//  - Views: TextureDesc::viewFormats lists the other formats a view may take; copies, uploads,
//    readback and barriers take the texture, not a view; views go before their texture. A view
//    between RGBA8 and BGRA8 orders (each with its sRGB twin) reads red and blue swapped, as the
//    bytes read in the other order, and is sampled only (GL swaps them by the view's swizzle).
// Shown by: texture_array_layers, cube_faces, cube_array, texture_3d_slices, render_to_subresource,
// render_cube_faces_then_sample, storage_texture_layers, generate_mips, copy_subresources,
// compressed_bc, msaa_resolve, transient_attachments, msaa_texel_fetch, msaa_copy,
// msaa_multiple_targets, view_mip_range,
// view_layer_and_face, view_format_srgb_unorm, view_swizzle, view_as_attachment, bgra8_formats,
// region_upload_row_pitch, region_copies, depth_stencil_buffer_copies, texture_copy_between_mips,
// shadow_compare_pcf, draw_indirect, dispatch_indirect.
//
// Pipelines and shaders
// ---------------------
// Pipelines are checked against their shaders (SPIR-V reflected with SPIRV-Cross, at
// createShader), before any native call and with the same Error on every backend:
//  - GraphicsPipelineDesc::bindings and ComputePipelineDesc::bindings may be left empty: the
//    slots are then every binding the shaders use, with its kind and stages. A list that is
//    given must name every slot a shader uses, with that kind and stage (an error names the
//    slot); slots the shaders do not use are allowed and must still be bound to draw.
//  - Every vertex shader input needs an attribute of its scalar kind (float or uint) in the
//    vertex layout; each later stage's inputs are outputs of the stage before it (location,
//    kind, enough components, per-patch alike); a fragment output landing on a colour target
//    has the target's kind; a compute work group fits maxComputeWorkGroupInvocations.
//  - Stages: vertex, [tessellation control + evaluation with PatchList and patchControlPoints],
//    [geometry], fragment, where DeviceFeatures::tessellationShaders / geometryShaders say so:
//      device->createGraphicsPipeline({.vertexShader = vs, .fragmentShader = fs,
//          .tessControlShader = tcs, .tessEvaluationShader = tes, .patchControlPoints = 4,
//          .geometryShader = gs, .topology = PrimitiveTopology::PatchList, ...});
//  - setPipeline in a pass: colorFormats, depthFormat and sampleCount equal the pass's.
//  - Binding setters: offsets are multiples of uniformBufferOffsetAlignment /
//    storageBufferOffsetAlignment and ranges at most maxUniformBufferRange / maxStorageBufferRange
//    (size 0: to the end, capped at the maximum); the kind of each slot is checked at the draw,
//    and a texture's kind is the one its shader declares (a Texture2D where the shader samples a
//    sampler2DArray is an Error: bind a view of that kind, createTextureView with .dimension).
//  - setTexture refuses a sampler that filters linearly (a Linear filter, no comparison) on a
//    format without FormatCaps::linearFilter (formatCaps() says what each format can do here).
//  - Feedback loops are Errors at the draw: a slot the pipeline reads may not hold a subresource
//    (mip, layer) that its render pass renders into or resolves to; other mips and layers of the
//    same texture may be read (render mip 1 while sampling a view of mip 0). The exception is
//    read-only depth: a pipeline that writes neither depth nor stencil may sample the depth
//    attachment (soft particles, decals). A pass may not name one subresource twice.
//  - What a shader declares is there to read: shaderInterface(shader) (ShaderReflection.h) lists
//    its bindings and each block's members with their offsets, and UniformBlock (UniformBlock.h)
//    writes a block by member name, as a port from glUniform* needs:
//      UniformBlock material(device->shaderInterface(fs), "Material");
//      material.set("tint", {1.0f, 0.5f, 0.0f});  device->writeBuffer(ubo, 0, material.bytes());
//    With validation, a uniform or storage range smaller than the block the pipeline declares at
//    its slot is a warning on stderr, once per message ("fe validation warning: slot 0 holds a
//    range of 16 bytes where pipeline 'x' declares a block of 32 bytes"; validate::warningCount):
//    Vulkan allows the smaller range while the shader reads no further, so it is not an Error.
// Shown by: pipeline_layout_from_shader, binding_mismatch_errors, storage_textures_at_any_slot,
// format_caps, vertex_formats, uniform_block_layout, geometry_stage, tessellation_stages.
//
// Per-draw constants and specialization
// -------------------------------------
//   cmd->setConstants(drawData);          // per-draw bytes (<= 128): FE_CONSTANTS(Name) { ... } in GLSL
//   device->createGraphicsPipeline({..., .specialization = {SpecializationConstant::of(0, 4u)}});
//  - Per-draw constants: std140, one block per stage, at most kMaxConstantBytes; each recording
//    starts with zeros and values persist across setPipeline. Vulkan push constants; GL a uniform
//    block at binding 64 fed from a ring (slots stay 0..63 for the application).
// Shown by: constants_per_draw, constants_errors, specialization.
//
// Queries
// -------
//   auto occlusion = device->createQuerySet({.type = QueryType::Occlusion, .count = 64});
//   cmd->beginQuery(occlusion, 0); ... cmd->endQuery(occlusion, 0);
//   device->queryResults(occlusion, 0, 1, samples);   // false until its submission completed
//  - Queries: a query is written once per submission (the device resets it before the
//    submission runs); occlusion queries inside one pass; none in secondary lists.
// Shown by: occlusion_query, pipeline_statistics, timestamps_in_query_set, query_errors,
// queries_across_lists.
//
// Pipeline cache
// --------------
//   device->openPipelineCache("pipelines.bin");         // or DeviceCreateDesc::pipelineCache
//  - Compiled pipelines (Vulkan's VkPipelineCache data, GL program binaries) kept across runs: a
//    file made for another device, driver or build is ignored, the stats' warning saying why
//    (PipelineCacheFile.h).
//  - Within a run, a pipeline equal to one the device made (every field, its shaders by their
//    code, not their handles) shares that one's native objects, also for a while after it was
//    destroyed (the last 128 unused are kept): a renderer made again compiles nothing twice.
//    pipelineCacheStats().shared counts them (PipelineSharing.h).
// Shown by: pipeline_cache_roundtrip; PipelineSharing tests.
//
// Captures
// --------
//   auto capture = FrameCapture::load("frame");         // RenderDoc (Backend.h), before createDevice
//   createDevice({.capture = "frame.fecap"});             // or FE_CAPTURE: every call into a file that
//   replayCapture("frame.fecap", *other);                 // replays on any backend (Capture.h)
//  - Every call of a device, with its data, into a file (Capture.h, docs/CAPTURE.md) that
//    replays on any backend; RenderDoc captures through FrameCapture (Backend.h).
// Shown by: recorded_list_replays (and the capture tests, tests/unit/CaptureTests.cpp).
//
// Fixed function
// --------------
// Where the APIs differ, every backend behaves as Vulkan does:
//  - FE_INSTANCE_ID (fe_common.glsl) counts from firstInstance, FE_VERTEX_ID from firstVertex.
//  - Points obey gl_PointSize; gl_PointCoord (0, 0) is the point's top-left texel.
//  - depthWrite without depthTest writes every fragment's depth (the test always passes).
//  - MipFilter::None reads level 0 and minifies with minFilter, magnifies with magFilter.
//  - MultisampleState::sampleMask with bit 0 clear draws nothing on a single-sample target;
//    bits beyond the sample count are ignored. A fragment shader's gl_SampleMask likewise: on a
//    single-sample target a fragment is kept when bit 0 is set.
//  - Flat-shaded (`flat`) outputs take the value of a primitive's first vertex (Vulkan's
//    provoking vertex; GL is set to its first-vertex convention).
//  - A colour target the fragment shader has no output for (or every target, without a fragment
//    shader) keeps its contents: the device masks its writes (the APIs leave it undefined).
//  - Blending a colour target whose format cannot be blended here (FormatCaps::blend: never the
//    integer formats) is an Error at createGraphicsPipeline; so is a shader declaring a texture
//    kind the device has none of (1D, buffer textures, multisampled arrays) at createShader.
//  - Primitive restart (strip topologies) uses the index 0xFFFF / 0xFFFFFFFF.
//  - New buffers and textures read as zeros (block-compressed textures excepted: upload them).
//  - readTexture of D24S8 gives depth in the low 24 bits and stencil in the high 8 of each
//    32-bit texel, of D32F_S8 a float depth and a word with stencil in its low 8 bits, of S8
//    (stencil only, an attachment where FormatCaps::renderTarget says so) one byte;
//    Image::texel returns depth in [0] and stencil in [1]. writeTexture takes depth and
//    depth-stencil texels in the same layout (Image::fromTexels makes them).
//  - Validation-layer and GL debug messages are printed once each; the count of repeats is
//    printed when the device is destroyed (validationErrorCount() counts every one).
// Shown by: first_instance, flat_first_vertex, unwritten_target_keeps_contents,
// point_size_and_coord, depth_write_without_test, mip_filter_none, sample_mask, shader_sample_mask,
// primitive_restart, zero_initialised, stencil8_and_readback, depth16, dynamic_blend_stencil_bias,
// stride_zero_vertex, border_color, lod_bias_and_clamp, depth_bias, depth_clamp.
//
// Windows
// -------
// Windows (vulkan-glfw, gl-glfw; Backend.h): show a texture on screen with present().
//   auto device = fe::gdi::createDevice({.backend = "auto", .window = true, .vsync = true});
//   while (device->present(target)) { /* render the next frame into target */ }  // false: closed
// present() takes an RGBA8 or RGBA8_SRGB texture with CopySrc usage and shows its bytes as they
// are (no sRGB conversion), upright, in a window sized to it (resized when the size changes).
// device->input() then says where the mouse is, which buttons and keys are down, each key's
// presses since the last present (a tap between two slow frames is not lost), how far the wheel
// turned, what was typed and which files were dropped on the window (InputState), for UIs and
// cameras (fe view).
// Shown by: the window tests (tests/unit/WindowTests.cpp), which need a display.
#pragma once

#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <ranges>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "fe/gdi/Format.h"
#include "fe/gdi/Image.h"

namespace fe::gdi {

// ---------------------------------------------------------------------------------------------
// Window input (Device::input): what an interactive application needs, the same on every
// windowed backend. Keys are the ones the engine's tools use.
// ---------------------------------------------------------------------------------------------
enum class Key : uint8_t {
    W,
    A,
    S,
    D,
    Q,
    E,
    R,
    F,
    P,
    Space,
    Escape,
    Tab,
    Enter,
    Backspace,
    Delete,
    Left,
    Right,
    Up,
    Down,
    Home,
    End,
    LeftShift,
    LeftControl,
    F1,
    F2,
    F12,
    Count
};
struct InputState {
    float mouseX = 0, mouseY = 0;  // framebuffer pixels from the window's top-left
    bool mouse[3] = {};            // left, right, middle button down
    float wheel = 0;  // scroll since the previous present (positive: away from the user)
    bool keys[size_t(Key::Count)] = {};
    std::string text;  // UTF-8 typed since the previous present
    // Presses per key since the previous present: a tap between two slow frames is not lost,
    // though `keys` (what is down as the frame samples it) never shows it.
    uint8_t presses[size_t(Key::Count)] = {};
    // Paths of the files dropped on the window since the previous present.
    std::vector<std::string> droppedFiles;
    bool down(Key k) const { return keys[size_t(k)]; }
    bool pressed(Key k) const { return presses[size_t(k)] > 0; }
};

// ---------------------------------------------------------------------------------------------
// Errors and handles
// ---------------------------------------------------------------------------------------------
struct ShaderInterface;  // ShaderReflection.h

struct Error : std::runtime_error {
    using std::runtime_error::runtime_error;
};
// The device is lost: recreate it (see "Errors and device loss" at the top).
struct DeviceLostError : Error {
    using Error::Error;
};

template <class Tag>
struct Handle {
    uint32_t id = 0;
    explicit operator bool() const { return id != 0; }
    friend bool operator==(Handle a, Handle b) { return a.id == b.id; }
};
using BufferHandle = Handle<struct BufferTag>;
using TextureHandle = Handle<struct TextureTag>;
using SamplerHandle = Handle<struct SamplerTag>;
using ShaderHandle = Handle<struct ShaderTag>;
using PipelineHandle = Handle<struct PipelineTag>;
using TimerHandle = Handle<struct TimerTag>;
using HeapHandle = Handle<struct HeapTag>;
using QuerySetHandle = Handle<struct QuerySetTag>;

// Data handed to the device always carries its length: a span of bytes, made with bytesOf().
using ByteSpan = std::span<const std::byte>;
template <class T>
ByteSpan bytesOf(const T& data) {
    if constexpr (std::ranges::contiguous_range<T>) {
        return std::as_bytes(std::span(std::ranges::data(data), std::ranges::size(data)));
    } else {
        static_assert(std::is_trivially_copyable_v<T>,
                      "bytesOf: plain data or a contiguous range of it");
        return {reinterpret_cast<const std::byte*>(&data), sizeof(T)};
    }
}

template <class E>
constexpr E operator|(E a, E b) requires std::is_enum_v<E> && requires {
    E::FlagsMarker;
}
{ return E(uint32_t(a) | uint32_t(b)); }
template <class E>
constexpr bool any(E a, E b) requires std::is_enum_v<E> && requires {
    E::FlagsMarker;
}
{ return (uint32_t(a) & uint32_t(b)) != 0; }

// ---------------------------------------------------------------------------------------------
// Buffers
// ---------------------------------------------------------------------------------------------
enum class BufferUsage : uint32_t {
    None = 0,
    Vertex = 1 << 0,
    Index = 1 << 1,
    Uniform = 1 << 2,
    Storage = 1 << 3,
    CopySrc = 1 << 4,
    CopyDst = 1 << 5,
    Indirect = 1 << 6,  // draw/dispatch arguments and draw counts (drawIndirect, dispatchIndirect)
    FlagsMarker = 0
};

enum class MemoryAccess : uint8_t {
    GpuOnly,   // written by writeBuffer (staged) or by the GPU
    Upload,    // CPU-writable, read by the GPU (per-frame constants)
    Readback,  // GPU-written, read by the CPU
};

struct BufferDesc {
    uint64_t size = 0;
    BufferUsage usage = BufferUsage::Vertex | BufferUsage::Index | BufferUsage::Uniform |
                        BufferUsage::Storage | BufferUsage::CopySrc | BufferUsage::CopyDst |
                        BufferUsage::Indirect;
    MemoryAccess access = MemoryAccess::GpuOnly;
    const char* debugName = nullptr;
};

// ---------------------------------------------------------------------------------------------
// Textures and samplers
// ---------------------------------------------------------------------------------------------
enum class TextureUsage : uint32_t {
    None = 0,
    Sampled = 1 << 0,
    RenderTarget = 1 << 1,  // colour or depth attachment, by format
    Storage = 1 << 2,
    CopySrc = 1 << 3,
    CopyDst = 1 << 4,
    // With RenderTarget only: contents live inside one render pass (loaded by Clear or DontCare,
    // stored DontCare, resolvable), never sampled, copied or read back. Vulkan makes it a
    // transient attachment in lazily allocated memory where the device has it
    // (DeviceFeatures::lazilyAllocatedMemory: tile GPUs keep it on chip); the render graph gives
    // it to attachments used by one pass only.
    Transient = 1 << 5,
    FlagsMarker = 0
};

// What a texture is, and so how shaders sample it (GLSL sampler2D, sampler2DArray, samplerCube,
// samplerCubeArray, sampler3D; the *Shadow variants with a comparison sampler).
enum class TextureDimension : uint8_t {
    Texture2D,
    Texture2DArray,
    TextureCube,       // 6 layers: +X, -X, +Y, -Y, +Z, -Z (the order of both APIs)
    TextureCubeArray,  // 6 layers per cube (DeviceFeatures::textureCubeArray)
    Texture3D,
};
const char* textureDimensionName(TextureDimension d);
// What a shader slot declares and a bound texture is, as one code: 1 + its TextureDimension, or
// kTexture2DMultisampleKind for a multisampled 2D texture (GLSL sampler2DMS); 0: no texture.
inline constexpr uint8_t kTexture2DMultisampleKind = 1 + uint8_t(TextureDimension::Texture3D) + 1;
const char* textureKindName(uint8_t kind);  // "Texture2D", ..., "Texture2D (multisampled)"

struct TextureDesc {
    TextureDimension dimension = TextureDimension::Texture2D;
    Format format = Format::RGBA8;
    uint32_t width = 1;
    uint32_t height = 1;
    // Texture3D: depth in texels (halved per mip); arrays: layer count; TextureCube: 6;
    // TextureCubeArray: 6 x the number of cubes; Texture2D: 1.
    uint32_t depthOrLayers = 1;
    uint32_t mipLevels = 1;
    // 1, 2, 4 or 8 where DeviceLimits::colorSampleCounts / depthSampleCounts has the bit; a
    // multisampled texture is a 2D render target with one mip, resolved into a single-sample one.
    uint32_t sampleCount = 1;
    TextureUsage usage = TextureUsage::Sampled | TextureUsage::CopyDst | TextureUsage::CopySrc;
    // Placed in a heap at an offset (memory aliasing, DeviceFeatures::memoryAliasing only);
    // null: the texture gets memory of its own.
    HeapHandle heap;
    uint64_t heapOffset = 0;
    // Formats, besides `format`, that views of this texture may have (formatsCompatible with it:
    // its sRGB/UNORM pair, or another uncompressed colour format of the same texel size).
    std::vector<Format> viewFormats;
    const char* debugName = nullptr;
};

// What a view's channel reads (TextureViewDesc::swizzle): itself, a constant, or another channel.
enum class Swizzle : uint8_t { Identity, Zero, One, R, G, B, A };

// A view of a texture (Device::createTextureView): a range of its mips and layers, seen as
// another kind or format. The view is a TextureHandle, bound wherever a texture is: sampled,
// storage (one mip of the view), attachment (mip and layer of the view). Kinds: Texture2D as
// 2D or 2D array; 2D array and cube (array) as 2D, 2D array, cube or cube array (a cube view is
// 6 layers of a square texture); 3D as 3D. A swizzled view is for sampling only. Copies,
// uploads, readback, mip generation and barriers address the texture itself, not its views;
// a texture's views are destroyed before it.
struct TextureViewDesc {
    std::optional<TextureDimension> dimension;  // default: the texture's
    Format format = Format::Undefined;       // default: the texture's; else one of its viewFormats
    uint32_t baseMip = 0, mipCount = 0;      // 0: to the last mip
    uint32_t baseLayer = 0, layerCount = 0;  // 0: to the last layer; 3D views take every slice
    std::array<Swizzle, 4> swizzle{};        // what r, g, b and a return
    const char* debugName = nullptr;
};

// A block of device memory that placed textures share; textures whose lifetimes do not
// overlap may occupy the same bytes (the render graph's transient aliasing).
struct HeapDesc {
    uint64_t size = 0;
    const char* debugName = nullptr;
};

struct TextureDesc;
// One image of a texture: a mip level and a layer (array layer; a cube face is layer % 6 of cube
// layer / 6; a 3D texture's depth slice within that mip level).
struct Subresource {
    uint32_t mipLevel = 0;
    uint32_t layer = 0;
};

// A box of texels in one mip level: columns [x, x + width), rows [y, y + height) of the array
// layers, cube faces (as Subresource::layer counts them) or 3D slices [z, z + depth). A width,
// height or depth of 0 reaches the edge of the mip level (the last layer or slice).
// Block-compressed formats: x, y, width and height are multiples of 4 or reach the edge.
// Buffer copies of depth/stencil textures move one aspect (aspectTexelBytes gives its layout):
// D16, D32F and S8 have one (All or its name); D24S8 and D32F_S8 need Depth or Stencil named.
struct TextureRegion {
    uint32_t mipLevel = 0;
    uint32_t x = 0, y = 0, z = 0;
    uint32_t width = 0, height = 0, depth = 0;
    TextureAspect aspect = TextureAspect::All;
};

// Where a region's texels lie in a buffer (or in writeTexture's data): from `offset`, rows of
// bytesPerRow bytes and rowsPerImage rows per layer or slice, top row first; 0 means tightly
// packed (one row of the region; the region's height). Rules, the same on every backend:
// offset is a multiple of 4 and of the texel size; bytesPerRow a multiple of the texel size and
// at least one row; rowsPerImage at least the region's height. Compressed formats are packed
// tightly (rows of 4x4 blocks).
struct TexelLayout {
    uint64_t offset = 0;
    uint32_t bytesPerRow = 0;
    uint32_t rowsPerImage = 0;
};

// Bytes of one subresource of mip level `mipLevel`, tightly packed (rows of blocks when compressed).
uint64_t textureByteSize(const TextureDesc& desc, uint32_t mipLevel);

struct MemoryRequirements {
    uint64_t size = 0;
    uint64_t alignment = 1;
};

enum class Filter : uint8_t { Nearest, Linear };
enum class MipFilter : uint8_t { None, Nearest, Linear };
enum class AddressMode : uint8_t { Repeat, MirroredRepeat, ClampToEdge, ClampToBorder };
// What ClampToBorder returns outside the texture (the three colours both APIs offer alike).
enum class BorderColor : uint8_t { TransparentBlack, OpaqueBlack, OpaqueWhite };

enum class CompareOp : uint8_t {
    Never,
    Less,
    Equal,
    LessOrEqual,
    Greater,
    NotEqual,
    GreaterOrEqual,
    Always
};

struct SamplerDesc {
    Filter minFilter = Filter::Linear;
    Filter magFilter = Filter::Linear;
    MipFilter mipFilter = MipFilter::None;
    AddressMode addressU = AddressMode::Repeat;
    AddressMode addressV = AddressMode::Repeat;
    AddressMode addressW = AddressMode::Repeat;  // 3D textures
    float maxAnisotropy = 1.0f;
    // Comparison sampler, for depth textures read through sampler2DShadow, sampler2DArrayShadow
    // or samplerCubeShadow: each texel fetched gives `reference compare texel` as 0 or 1, and
    // Linear filtering averages those results (hardware PCF), not the depths.
    bool compareEnable = false;
    CompareOp compare = CompareOp::LessOrEqual;
    BorderColor borderColor = BorderColor::TransparentBlack;  // AddressMode::ClampToBorder
    // Level of detail: the computed one (or textureLod's) plus lodBias, clamped to
    // [minLod, maxLod], as both APIs define it. lodBias in [-16, 16]; 0 <= minLod <= maxLod.
    // MipFilter::None reads level 0 whatever these say.
    float lodBias = 0.0f;
    float minLod = 0.0f;
    float maxLod = 1000.0f;
    const char* debugName = nullptr;
};

// ---------------------------------------------------------------------------------------------
// Shaders and pipelines
// ---------------------------------------------------------------------------------------------
// A graphics pipeline runs vertex, [tessellation control, tessellation evaluation], [geometry],
// fragment (DeviceFeatures::tessellationShaders, geometryShaders). Shader files: .vert, .tesc,
// .tese, .geom, .frag, .comp.
enum class ShaderStage : uint32_t {
    None = 0,
    Vertex = 1 << 0,
    Fragment = 1 << 1,
    Compute = 1 << 2,
    Geometry = 1 << 3,
    TessControl = 1 << 4,
    TessEvaluation = 1 << 5,
    AllGraphics = Vertex | Fragment | Geometry | TessControl | TessEvaluation,
    All = AllGraphics | Compute,
    FlagsMarker = 0
};

// SPIR-V for both targets, compiled at build time from one GLSL 450 source (see shaders/).
struct ShaderBinary {
    const char* name = "";
    std::span<const uint32_t> vulkan;  // glslang -V (graphics stages: then spirv-opt -O)
    std::span<const uint32_t> opengl;  // glslang -G (likewise), loaded through ARB_gl_spirv
};

// GLSL or HLSL source compiled at createShader instead of a binary (ShaderCompiler.h: both
// encodings, an unchanged source compiled once per process, errors as the build step's
// "NAME:LINE: message"). HLSL's entry point is ShaderDesc::entryPoint (PORTING: its conventions).
enum class ShaderLanguage : uint8_t { GLSL, HLSL };
struct ShaderSource {
    std::string_view text;  // GLSL 450 or HLSL (Shader Model 5/6); empty: ShaderDesc::binary
    ShaderLanguage language = ShaderLanguage::GLSL;
    const char* name = "shader";
    std::vector<std::string> defines;  // "NAME" or "NAME=VALUE"
    // `#include "NAME"` beyond the built-in fe_common.glsl: NAME's text, or nullopt.
    std::function<std::optional<std::string>(const std::string& name, const std::string& includer)>
        include;
};

struct ShaderDesc {
    ShaderStage stage = ShaderStage::None;
    ShaderBinary binary;
    const char* entryPoint = "main";
    ShaderSource source;  // instead of binary: compiled at createShader
};

enum class BindingType : uint8_t { UniformBuffer, StorageBuffer, SampledTexture, StorageTexture };

// Per-draw constants (CommandList::setConstants): at most this many bytes per pipeline, in one
// block declared through the engine include (fe_common.glsl), std140 rules on every backend:
//   FE_CONSTANTS(DrawConstants) { mat4 model; vec4 tint; } draw;   // then draw.model, draw.tint
// It is a push-constant block on Vulkan and a uniform block at a reserved binding on GL (fed
// per draw from a ring of uniform memory); the pipeline takes its size from the shaders.
inline constexpr uint32_t kMaxConstantBytes = 128;

// A specialization constant's value for a pipeline: `layout(constant_id = id) const T name =
// default;` in GLSL takes it in every stage of the pipeline that declares that id, when the
// pipeline is made (Vulkan VkSpecializationInfo, GL glSpecializeShader), so one SPIR-V pair
// serves every value. bool, int, uint and float constants; an id no stage declares, a value of
// the wrong kind (a bool other than 0 or 1) or an id given twice is an Error.
struct SpecializationConstant {
    uint32_t id = 0;
    uint32_t bits = 0;  // the value's 32 bits
    template <class T>
    static SpecializationConstant of(uint32_t id, T value) {
        static_assert(std::is_same_v<T, bool> || std::is_same_v<T, int32_t> ||
                          std::is_same_v<T, uint32_t> || std::is_same_v<T, float>,
                      "specialization constants are bool, int32_t, uint32_t or float");
        if constexpr (std::is_same_v<T, bool>)
            return {id, value ? 1u : 0u};
        else
            return {id, std::bit_cast<uint32_t>(value)};
    }
};

struct BindingSlot {
    uint32_t slot = 0;  // `layout(binding = slot)`
    BindingType type = BindingType::UniformBuffer;
    ShaderStage stages = ShaderStage::All;
};

struct VertexAttribute {
    uint32_t location = 0;
    VertexFormat format = VertexFormat::Float3;
    uint32_t offset = 0;
};

struct VertexBufferLayout {
    uint32_t stride = 0;  // 0: every vertex (or instance) reads the same element
    bool perInstance = false;
    std::vector<VertexAttribute> attributes;
};

enum class PrimitiveTopology : uint8_t {
    TriangleList,
    TriangleStrip,
    LineList,
    LineStrip,
    PointList,
    PatchList,  // tessellation: GraphicsPipelineDesc::patchControlPoints vertices per patch
};
enum class CullMode : uint8_t { None, Front, Back };
enum class FrontFace : uint8_t { CounterClockwise, Clockwise };
enum class StencilOp : uint8_t {
    Keep,
    Zero,
    Replace,
    IncrementClamp,
    DecrementClamp,
    Invert,
    IncrementWrap,
    DecrementWrap
};
enum class BlendFactor : uint8_t {
    Zero,
    One,
    SrcColor,
    OneMinusSrcColor,
    DstColor,
    OneMinusDstColor,
    SrcAlpha,
    OneMinusSrcAlpha,
    DstAlpha,
    OneMinusDstAlpha,
    ConstantColor,
    OneMinusConstantColor
};
enum class BlendOp : uint8_t { Add, Subtract, ReverseSubtract, Min, Max };
enum class ColorMask : uint8_t { None = 0, R = 1, G = 2, B = 4, A = 8, All = 15, FlagsMarker = 0 };

struct RasterState {
    CullMode cullMode = CullMode::None;
    FrontFace frontFace = FrontFace::CounterClockwise;
    // Depth bias (shadow maps): offset = depthBiasSlope * m + depthBiasConstant * r, where m is
    // the primitive's maximum depth slope and r the smallest resolvable difference of the depth
    // format (D32F: 2^(e - 23) for the primitive's largest exponent e), then clamped to
    // +-depthBiasClamp when that is not 0. Identical formula on Vulkan and GL. For the UNORM
    // formats (D16, D24S8) both APIs let the driver choose r between 2^-n and 2 x 2^-n for n
    // depth bits: llvmpipe and lavapipe take 2 x 2^-n, so size a constant bias for that.
    float depthBiasConstant = 0.0f;
    float depthBiasSlope = 0.0f;
    float depthBiasClamp = 0.0f;
    // Fragments beyond the near/far planes are kept with depth clamped to the viewport's range
    // instead of clipped (shadow casters behind the light's near plane). DeviceFeatures::depthClamp.
    bool depthClamp = false;
};

struct MultisampleState {
    uint32_t sampleCount = 1;      // must equal the sample count of every attachment in the pass
    bool alphaToCoverage = false;  // the first output's alpha becomes a coverage mask
    uint32_t sampleMask =
        ~0u;  // bit i clear: sample i is never written (bit 0: single-sample targets)
};

struct StencilFaceState {
    StencilOp failOp = StencilOp::Keep;
    StencilOp depthFailOp = StencilOp::Keep;
    StencilOp passOp = StencilOp::Keep;
    CompareOp compare = CompareOp::Always;
};

struct DepthStencilState {
    bool depthTest = false;
    bool depthWrite = false;
    CompareOp depthCompare = CompareOp::Less;
    bool stencilTest = false;
    StencilFaceState front;
    StencilFaceState back;
    uint8_t stencilReadMask = 0xff;
    uint8_t stencilWriteMask = 0xff;
    uint8_t stencilReference = 0;
};

struct BlendTargetState {
    bool enable = false;
    BlendFactor srcColor = BlendFactor::One;
    BlendFactor dstColor = BlendFactor::Zero;
    BlendOp colorOp = BlendOp::Add;
    BlendFactor srcAlpha = BlendFactor::One;
    BlendFactor dstAlpha = BlendFactor::Zero;
    BlendOp alphaOp = BlendOp::Add;
    ColorMask writeMask = ColorMask::All;
};

struct GraphicsPipelineDesc {
    ShaderHandle vertexShader;
    ShaderHandle fragmentShader;  // may be null for depth-only passes
    // Tessellation: both or neither (DeviceFeatures::tessellationShaders), with topology
    // PatchList and patchControlPoints (1 to limits.maxTessellationPatchSize) vertices a patch.
    ShaderHandle tessControlShader;
    ShaderHandle tessEvaluationShader;
    uint32_t patchControlPoints = 0;
    // After the vertex (or tessellation) stages: DeviceFeatures::geometryShaders.
    ShaderHandle geometryShader;
    std::vector<VertexBufferLayout> vertexBuffers;
    PrimitiveTopology topology = PrimitiveTopology::TriangleList;
    // Strip topologies, indexed draws: the index 0xFFFF (U16) or 0xFFFFFFFF (U32) ends a strip
    // and starts the next.
    bool primitiveRestart = false;
    RasterState raster;
    MultisampleState multisample;
    DepthStencilState depthStencil;
    std::vector<BlendTargetState> blend;  // one per colour target; missing entries: no blending
    float blendConstant[4] = {0, 0, 0, 0};
    std::vector<Format> colorFormats;
    Format depthFormat = Format::Undefined;
    std::vector<BindingSlot> bindings;
    std::vector<SpecializationConstant> specialization;  // see SpecializationConstant
    const char* debugName = nullptr;
};

struct ComputePipelineDesc {
    ShaderHandle computeShader;
    std::vector<BindingSlot> bindings;
    std::vector<SpecializationConstant> specialization;  // see SpecializationConstant
    const char* debugName = nullptr;
};

// ---------------------------------------------------------------------------------------------
// Render passes
// ---------------------------------------------------------------------------------------------
enum class LoadOp : uint8_t { Clear, Load, DontCare };
enum class StoreOp : uint8_t { Store, DontCare };

// An attachment is one subresource: rendering goes to one mip level of one layer (array layer,
// cube face or 3D slice). A multisampled attachment may name a single-sample resolve target of
// the same format and size, written at the end of the pass.
struct ColorAttachment {
    TextureHandle texture;
    uint32_t mipLevel = 0;
    uint32_t layer = 0;
    LoadOp load = LoadOp::Clear;
    StoreOp store = StoreOp::Store;
    float clear[4] = {0, 0, 0, 0};
    TextureHandle resolveTexture;  // the average of each pixel's samples
    Subresource resolveSubresource;
};

struct DepthAttachment {
    TextureHandle texture;  // null: no depth attachment
    uint32_t mipLevel = 0;
    uint32_t layer = 0;
    LoadOp load = LoadOp::Clear;
    StoreOp store = StoreOp::Store;
    float clearDepth = 1.0f;
    uint8_t clearStencil = 0;
    // Depth resolve takes sample 0 of each pixel: the one mode every Vulkan device supports
    // (VK_RESOLVE_MODE_SAMPLE_ZERO_BIT), and a depth some surface really has, where an average
    // of an edge pixel's samples would be the depth of no surface at all.
    TextureHandle resolveTexture;
    Subresource resolveSubresource;
};

struct RenderPassDesc {
    std::vector<ColorAttachment> colors;
    DepthAttachment depth;
    const char* debugName = nullptr;
    // The pass executes secondary lists (CommandList::beginSecondary, executeSecondary), with
    // the primary's own draws before, between and after them.
    bool secondaryLists = false;
};

struct Viewport {
    float x = 0, y = 0, width = 0, height = 0, minDepth = 0, maxDepth = 1;
};
struct Rect {
    int32_t x = 0, y = 0;
    uint32_t width = 0, height = 0;
};

enum class IndexType : uint8_t { U16, U32 };

// Indirect argument records, tightly packed, as both APIs read them from BufferUsage::Indirect
// buffers (a compute shader may write them).
struct DrawIndirectArgs {
    uint32_t vertexCount = 0, instanceCount = 0, firstVertex = 0, firstInstance = 0;
};
struct DrawIndexedIndirectArgs {
    uint32_t indexCount = 0, instanceCount = 0, firstIndex = 0;
    int32_t baseVertex = 0;
    uint32_t firstInstance = 0;
};
struct DispatchIndirectArgs {
    uint32_t groupsX = 0, groupsY = 0, groupsZ = 0;
};

// ---------------------------------------------------------------------------------------------
// Queries
// ---------------------------------------------------------------------------------------------
//   auto occlusion = device->createQuerySet({.type = QueryType::Occlusion, .count = 64});
//   cmd->beginQuery(occlusion, i); cmd->drawIndexed(...); cmd->endQuery(occlusion, i);  // in a pass
//   std::vector<uint64_t> samples(64);
//   if (device->queryResults(occlusion, 0, 64, samples)) { /* the frame's counts, no waiting */ }
//   cmd->resolveQueries(occlusion, 0, 64, buffer, 0);  // or into a buffer on the GPU
enum class QueryType : uint8_t {
    Occlusion,  // samples that passed the depth and stencil tests, exactly (x samples per pixel)
    AnySamplesPassed,    // 1 when any sample passed, else 0 (resolveQueries: 0 or non-zero)
    PipelineStatistics,  // a PipelineStatistics per query (DeviceFeatures::pipelineStatistics)
    Timestamp,  // the GPU clock when the work recorded before it has finished (writeTimestamp)
};
const char* queryTypeName(QueryType t);

struct QuerySetDesc {
    QueryType type = QueryType::Occlusion;
    uint32_t count = 1;  // queries 0 .. count - 1, at most 4096
    const char* debugName = nullptr;
};

// What a PipelineStatistics query counts between beginQuery and endQuery, in this order (the
// layout resolveQueries writes, 32 bytes per query). Counts of invocations are what the GPU
// ran: a vertex shader may run fewer times than vertices (reuse) and a fragment shader more
// times than pixels (helper invocations); primitives and compute invocations are exact.
struct PipelineStatistics {
    uint64_t primitives = 0;  // primitives assembled from the draws' vertices
    uint64_t vertexInvocations = 0;
    uint64_t fragmentInvocations = 0;
    uint64_t computeInvocations = 0;
};

// ---------------------------------------------------------------------------------------------
// Queues
// ---------------------------------------------------------------------------------------------
// Every device has three queues; a command list is made for one (CommandListDesc::queue) and
// submitted to it. What a list may record depends on its queue, on every backend (Vulkan's
// queue capabilities, checked when the command is recorded, with the same Error everywhere):
//  - Graphics: everything.
//  - Compute: dispatches, copies, clearBuffer, barriers, queries outside passes, timers,
//    resolveQueries, debug groups: no render passes, generateMips or resolveTexture.
//  - Copy: copies, clearBuffer, barriers and debug groups only.
// Submissions to one queue run in submission order. Submissions to different queues are ordered
// only where the program says so, with SubmitDesc::waitFor: that submission starts once the
// fence's submission and every earlier one (on every queue) have completed, and sees all their
// writes. Where DeviceFeatures::asyncCompute / asyncCopy are true the queue is a hardware queue
// of its own (a Vulkan queue family or queue beside the graphics one) and its work may overlap
// the graphics queue's; elsewhere (GL: one context; lavapipe: one queue) it shares the
// graphics queue and runs in submission order, which satisfies every waitFor by itself. Fences
// count submissions across all queues: wait(f) waits for f and every submission before it.
// Device transfers (writeBuffer, writeTexture, readBuffer, readTexture, initial data) are
// ordered after the work of every queue submitted before them. present() shows what the
// graphics queue wrote: a texture another queue writes reaches it through a graphics submission
// that waits for that queue's fence.
//   auto upload = device->createCommandList({.queue = QueueKind::Copy});
//   upload->copyBufferToTexture(texture, {}, staging, 0);
//   FenceValue uploaded = device->submit(*upload);                  // runs beside the frame
//   FenceValue drawn = device->submit(*frame, {.waitFor = uploaded}); // samples `texture`
// Shown by: compute_queue (a compute list recorded and submitted on another thread), copy_queue.
enum class QueueKind : uint8_t { Graphics, Compute, Copy };
const char* queueKindName(QueueKind q);  // "graphics", "compute", "copy"

// ---------------------------------------------------------------------------------------------
// Command recording
// ---------------------------------------------------------------------------------------------
// Recording is not executing, on every backend (Vulkan's model). A CommandList records; nothing
// it records runs before Device::submit, submitted lists run in submission order, and a list
// that is never submitted has no effect. What a command reads (buffer contents, texture texels)
// is read when the work runs on the GPU, not when it is recorded. Mistakes are still reported
// where they are made: each call validates its arguments and throws gdi::Error while recording.
// After submit the list is empty and records anew (its bindings and pass state are reset).
//
// Threads: a CommandList may be recorded on any thread, and several lists on several threads
// at once, one thread per list at a time (a list may move to another thread between calls).
// With DeviceCreateDesc::validation a call made while another thread is inside a call of the
// same list (submit and executeSecondary count as calls of every list they take) throws Error
// on every backend, and the list is unharmed; without validation that is undefined, as in
// Vulkan without its layer (the check's cost: ExclusiveUse.h). Every Device member may be
// called from any thread; the device serialises what it must (see Device). By default
// synchronisation between passes, dispatches and copies is the backend's job (a conservative
// barrier after each write).
// A caller that knows every access, the render graph, turns that off with
// setAutomaticBarriers(false) and states each texture's and buffer's change with barrier().

// What a texture is being used for, as far as synchronisation is concerned.
enum class ResourceState : uint8_t {
    Undefined,     // contents not needed (first use of transient or aliased memory)
    RenderTarget,  // colour attachment
    DepthTarget,   // depth/stencil attachment
    ShaderRead,    // sampled in a shader
    Storage,       // read/written as a storage image
    CopySrc,
    CopyDst,
};
const char* resourceStateName(ResourceState s);

// A state change of a texture's subresources: mips [baseMip, baseMip + mipCount) of layers
// [baseLayer, baseLayer + layerCount); a count of 0 means "to the last one". Undefined as
// `before` drops those subresources' contents (the whole texture on GL, which cannot drop less).
struct TextureBarrier {
    TextureHandle texture;
    ResourceState before = ResourceState::Undefined;
    ResourceState after = ResourceState::ShaderRead;
    uint32_t baseMip = 0, mipCount = 0;
    uint32_t baseLayer = 0, layerCount = 0;
};

// How a command reads or writes a buffer, as far as synchronisation is concerned (flags).
enum class BufferAccess : uint32_t {
    None = 0,
    Vertex = 1 << 0,
    Index = 1 << 1,
    Indirect = 1 << 2,  // draw/dispatch arguments and draw counts
    Uniform = 1 << 3,
    StorageRead = 1 << 4,
    StorageWrite = 1 << 5,
    CopySrc = 1 << 6,
    CopyDst = 1 << 7,
    FlagsMarker = 0
};
// Work after the barrier that accesses [offset, offset + size) of the buffer as `after` waits
// for work before it that accessed it as `before` (size 0: to the end).
struct BufferBarrier {
    BufferHandle buffer;
    BufferAccess before = BufferAccess::StorageWrite;
    BufferAccess after = BufferAccess::StorageRead;
    uint64_t offset = 0, size = 0;
};
class CommandList {
public:
    virtual ~CommandList() = default;

    // A render pass starts with no pipeline bound: call setPipeline in every pass. Bindings
    // (buffers, textures) persist for the whole recording.
    virtual void beginRenderPass(const RenderPassDesc& desc) = 0;
    virtual void endRenderPass() = 0;

    virtual void setPipeline(PipelineHandle pipeline) = 0;
    // Viewports are finite with a positive width and height and depths in [0, 1] (Vulkan's
    // negative-height y flip is an Error: clip space is already Vulkan's, y down, so flip y in
    // the projection). A scissor partly outside the target (negative offsets too) clips to it.
    virtual void setViewport(const Viewport& viewport) = 0;  // default: whole render area
    virtual void setScissor(const Rect& rect) = 0;           // default: whole render area
    // Pipeline state that may also change between draws. Each pass starts from its pipelines'
    // values (GraphicsPipelineDesc::blendConstant, DepthStencilState::stencilReference,
    // RasterState's depth bias), which setPipeline applies; once the pass sets one of these, the
    // value stays, across later setPipeline calls too, until it is set again or the pass ends
    // (WebGPU's rule, and Vulkan's for dynamic state): set before setPipeline, it is not lost.
    // Viewport, scissor and these are set inside a render pass (outside one they are an Error:
    // each pass starts from the render area and its pipelines' values).
    virtual void setBlendConstant(const std::array<float, 4>& rgba) = 0;
    virtual void setStencilReference(uint8_t reference) = 0;
    virtual void setDepthBias(float constant, float slope, float clamp = 0.0f) = 0;
    // Per-draw constants: bytes [offset, offset + data.size()) of the constants block
    // (FE_CONSTANTS, kMaxConstantBytes at most), read by the draws and dispatches that follow.
    // Offset and size are multiples of 4. Each recording (and each secondary list) starts with
    // all 128 bytes zero; values persist across setPipeline, and a pipeline reads the first
    // bytes its block declares. Cheaper per draw than a uniform buffer at a new offset.
    virtual void setConstants(uint32_t offset, ByteSpan data) = 0;
    template <class T>
    void setConstants(const T& data) {
        setConstants(0, bytesOf(data));
    }
    // Vertex buffers 0 to 15; an index buffer's offset is a multiple of its index size. Each
    // draw checks that every buffer its pipeline's layout names is bound, that a non-indexed
    // draw's vertices and every draw's instances lie inside them, and that an indexed draw's
    // indices lie inside the index buffer (the vertices indices pick are the GPU's business).
    virtual void setVertexBuffer(uint32_t index, BufferHandle buffer, uint64_t offset = 0) = 0;
    virtual void setIndexBuffer(BufferHandle buffer, IndexType type, uint64_t offset = 0) = 0;

    // Resource bindings, by slot (`layout(binding = slot)`, 0 to 63 for every kind, on every
    // backend). size 0 means "to the end". A pipeline's shaders may use at most
    // limits.maxStorageTextures storage textures (GL image units: 8 on NVIDIA), at any slots.
    virtual void setUniformBuffer(uint32_t slot, BufferHandle buffer, uint64_t offset = 0,
                                  uint64_t size = 0) = 0;
    virtual void setStorageBuffer(uint32_t slot, BufferHandle buffer, uint64_t offset = 0,
                                  uint64_t size = 0) = 0;
    virtual void setTexture(uint32_t slot, TextureHandle texture, SamplerHandle sampler) = 0;
    virtual void setStorageTexture(uint32_t slot, TextureHandle texture, uint32_t mipLevel = 0) = 0;

    virtual void draw(uint32_t vertexCount, uint32_t instanceCount = 1, uint32_t firstVertex = 0,
                      uint32_t firstInstance = 0) = 0;
    virtual void drawIndexed(uint32_t indexCount, uint32_t instanceCount = 1,
                             uint32_t firstIndex = 0, int32_t baseVertex = 0,
                             uint32_t firstInstance = 0) = 0;
    // At most limits.maxComputeWorkGroupCount groups along each axis.
    virtual void dispatch(uint32_t groupsX, uint32_t groupsY = 1, uint32_t groupsZ = 1) = 0;

    // Indirect work: drawCount records of `stride` bytes from `offset` in an Indirect buffer.
    // drawCount > 1 needs DeviceFeatures::multiDrawIndirect. The *Count forms read the number of
    // draws (a uint32) from countBuffer at countOffset, capped at maxDrawCount
    // (DeviceFeatures::drawIndirectCount; elsewhere they throw Error).
    virtual void drawIndirect(BufferHandle args, uint64_t offset, uint32_t drawCount = 1,
                              uint32_t stride = sizeof(DrawIndirectArgs)) = 0;
    virtual void drawIndexedIndirect(BufferHandle args, uint64_t offset, uint32_t drawCount = 1,
                                     uint32_t stride = sizeof(DrawIndexedIndirectArgs)) = 0;
    virtual void drawIndirectCount(BufferHandle args, uint64_t offset, BufferHandle countBuffer,
                                   uint64_t countOffset, uint32_t maxDrawCount,
                                   uint32_t stride = sizeof(DrawIndirectArgs)) = 0;
    virtual void drawIndexedIndirectCount(BufferHandle args, uint64_t offset,
                                          BufferHandle countBuffer, uint64_t countOffset,
                                          uint32_t maxDrawCount,
                                          uint32_t stride = sizeof(DrawIndexedIndirectArgs)) = 0;
    virtual void dispatchIndirect(BufferHandle args, uint64_t offset) = 0;

    // Fills mip levels 1.. of every layer from level 0 with a 2x2 (3D: 2x2x2) box filter, on the
    // GPU. The format must support linear filtering. Outside render passes.
    virtual void generateMips(TextureHandle texture) = 0;

    // Copies check usage: what a command reads needs CopySrc (buffers and textures), what it
    // writes CopyDst (copies, resolveQueries; clearBuffer CopyDst or Storage, as Vulkan fills
    // through a transfer and D3D12 through a storage view); an Error names the object and the
    // usage it was created with. The device's own transfers (writeBuffer, writeTexture,
    // readBuffer, readTexture, initial data) and generateMips need no copy usage.
    // Within one buffer the two ranges must not overlap.
    virtual void copyBuffer(BufferHandle dst, uint64_t dstOffset, BufferHandle src,
                            uint64_t srcOffset, uint64_t size) = 0;
    // Fills [offset, offset + size) of the buffer with the 32-bit pattern `value` (0: zeros);
    // size 0 means to the end. Offset and size are multiples of 4 (vkCmdFillBuffer's rule).
    // Outside render passes.
    virtual void clearBuffer(BufferHandle buffer, uint64_t offset = 0, uint64_t size = 0,
                             uint32_t value = 0) = 0;
    // Whole-texture copies of one mip level (every layer); descriptions must match.
    virtual void copyTexture(TextureHandle dst, TextureHandle src, uint32_t mipLevel = 0) = 0;
    // One subresource, tightly packed rows, top to bottom (see textureByteSize); of the
    // depth/stencil formats those with one aspect (D16, D32F, S8) in that aspect's layout.
    virtual void copyBufferToTexture(TextureHandle dst, Subresource at, BufferHandle src,
                                     uint64_t srcOffset) = 0;
    virtual void copyTextureToBuffer(BufferHandle dst, uint64_t dstOffset, TextureHandle src,
                                     Subresource at) = 0;
    // Regions (TextureRegion, TexelLayout): colour formats, compressed ones packed tightly, and
    // one aspect of a depth/stencil format (TextureRegion::aspect; aspectTexelBytes gives the
    // texel: D24S8's depth is 4 bytes with the depth in the low 24 bits, every stencil 1 byte).
    // Copying depth into a float format (D32F, D32F_S8) takes values in [0, 1] (Vulkan leaves
    // others undefined). Multisampled textures are not copied by region (resolve them).
    virtual void copyBufferToTexture(TextureHandle dst, const TextureRegion& region,
                                     BufferHandle src, const TexelLayout& layout) = 0;
    virtual void copyTextureToBuffer(BufferHandle dst, const TexelLayout& layout, TextureHandle src,
                                     const TextureRegion& region) = 0;
    // Copies srcRegion of src to dst at dstAt's mip level and origin (its extent is srcRegion's):
    // between mips, layers or places of one texture (the two boxes must not overlap) or between
    // textures of compatible formats (formatsCompatible), both 3D or both layered. Outside passes.
    virtual void copyTexture(TextureHandle dst, const TextureRegion& dstAt, TextureHandle src,
                             const TextureRegion& srcRegion) = 0;
    // Averages the samples of srcRegion of a multisampled texture into dst at dstAt's mip level,
    // layer and origin (the extent is srcRegion's): a render pass's resolve, by region and
    // outside passes. One colour format (not integer), src CopySrc and dst CopyDst usage.
    virtual void resolveTexture(TextureHandle dst, const TextureRegion& dstAt, TextureHandle src,
                                const TextureRegion& srcRegion) = 0;

    virtual void beginTimer(TimerHandle timer) = 0;
    virtual void endTimer(TimerHandle timer) = 0;

    // Queries (QuerySetDesc). Occlusion and AnySamplesPassed queries begin and end inside one
    // render pass; PipelineStatistics queries begin and end both inside one pass or both outside
    // (then they may span passes and dispatches). One query of each type is active at a time.
    // A query is written at most once per submission (the device resets the queries a
    // submission uses before it runs) and not in secondary lists.
    virtual void beginQuery(QuerySetHandle set, uint32_t index) = 0;
    virtual void endQuery(QuerySetHandle set, uint32_t index) = 0;
    // Timestamp sets: the GPU time once the work recorded before has finished. Outside passes.
    virtual void writeTimestamp(QuerySetHandle set, uint32_t index) = 0;
    // Copies the results of queries [first, first + count) into dst at dstOffset (a multiple of 8; CopyDst usage) as uint64_t values: one
    // per query, four (PipelineStatistics) for statistics; timestamps in DeviceLimits::
    // timestampPeriodNs units. The GPU waits for the queries, not the CPU. Outside passes.
    // Each query ended earlier in this recording, in an earlier list of the submission, or (when
    // no list of the submission writes it) in an earlier submission: its last result. Otherwise
    // submit throws (the resolve would wait for a write the submission's reset erases).
    virtual void resolveQueries(QuerySetHandle set, uint32_t first, uint32_t count,
                                BufferHandle dst, uint64_t dstOffset) = 0;
    virtual void pushDebugGroup(const char* name) = 0;
    virtual void popDebugGroup() = 0;
    // One marker at this point of the recording (a frame debugger shows it among the calls).
    virtual void insertDebugLabel(const char* name) = 0;

    // The texture's previous contents are no longer needed: required before the first use of
    // a heap-placed texture whose memory another texture may have written since (Vulkan:
    // layout from UNDEFINED; GL: glInvalidateTexImage). Outside render passes.
    virtual void discardTexture(TextureHandle texture) = 0;

    // Explicit synchronisation. While automatic barriers are off the backend inserts no
    // hazard barriers between passes, dispatches and copies of this recording; the caller
    // orders every dependency with barrier(). Turning them back on orders everything
    // recorded so far before what follows. Submitting always makes the results visible to
    // later submissions and to readback. Outside render passes. A barrier names only states
    // the resource's usage allows, before and after: RenderTarget / DepthTarget need
    // RenderTarget usage and a colour / depth format, ShaderRead Sampled or Storage, Storage
    // Storage; a buffer access its usage (StorageRead and StorageWrite: Storage). Anything else
    // is an Error, as a state the resource is never in. CopySrc and CopyDst go with any usage:
    // writeTexture / writeBuffer are copies into any resource (a barrier from CopyDst after one
    // is true, though not needed: device transfers are ordered for you).
    virtual void setAutomaticBarriers(bool enabled) = 0;
    virtual void barrier(const TextureBarrier* barriers, uint32_t count) = 0;
    virtual void barrier(const BufferBarrier* barriers, uint32_t count) = 0;
    void barrier(const TextureBarrier& b) { barrier(&b, 1); }
    void barrier(const BufferBarrier& b) { barrier(&b, 1); }

    // Secondary lists: draws of one pass recorded on several threads, or once and replayed every
    // frame (Vulkan's secondary command buffers, Metal's indirect command buffers, D3D12 and
    // WebGPU bundles):
    //   primary->beginRenderPass({.colors = ..., .secondaryLists = true});
    //   // on each worker thread (or once, at load), for a pass of the same kind:
    //   part->beginSecondary(pass); part->setPipeline(p); ... part->draw(...); part->endSecondary();
    //   primary->draw(...);                  // the primary's own draws, before, between, after
    //   primary->executeSecondary(parts);    // after the workers are done
    //   primary->endRenderPass();
    // beginSecondary starts a secondary recording on an empty list (or on an ended secondary
    // list, whose old recording it replaces); until endSecondary it may record what a pass may
    // hold (pipeline, viewport, scissor, vertex/index buffers, bindings, draws, balanced debug
    // groups), starting from the pass's render area as viewport and scissor, no pipeline and no
    // bindings of its own. executeSecondary checks each list was begun for a pass of the same
    // formats, sample count and size and runs its recording there, when the primary's
    // submission runs; the list keeps it, so it runs again in any compatible pass of any later
    // recording (a list recorded anew meanwhile leaves the submissions that ran the old one
    // alone). A secondary list cannot be submitted itself. After each executeSecondary, and
    // after the pass, the primary's pipeline, bindings, vertex and index buffers are unset and
    // its viewport and scissor are the render area (Vulkan leaves them undefined): set them
    // again before its next draw. Objects a secondary list uses stay alive while it is executed
    // (a destroyed one makes the submit fail, as for any recording).
    virtual void beginSecondary(const RenderPassDesc& pass) = 0;
    virtual void endSecondary() = 0;
    // Drops what the list holds (an unsubmitted recording, or a secondary list's recording:
    // primaries that executed it keep theirs): the list is as new, for either use again.
    virtual void reset() = 0;
    virtual void executeSecondary(std::span<CommandList* const> lists) = 0;
    void executeSecondary(CommandList& list) {
        CommandList* l = &list;
        executeSecondary(std::span<CommandList* const>(&l, 1));
    }

    // The queue the list was made for (CommandListDesc::queue); reset() keeps it.
    virtual QueueKind queue() const = 0;

    // Escape hatch (interop, and bench/ measuring the abstraction against direct API calls):
    // the VkCommandBuffer being recorded, 0 on backends without one.
    virtual uint64_t nativeCommandBuffer() { return 0; }
};

// What Device::nativeObject returns: a Vk handle (cast to uint64_t) or a GL object name.
enum class NativeObject : uint8_t {
    Device,          // VkDevice
    PhysicalDevice,  // VkPhysicalDevice
    Queue,           // VkQueue
    QueueFamily,     // queue family index
    Buffer,          // VkBuffer / GL buffer name
    Texture,         // VkImage / GL texture name
    TextureView,     // VkImageView (all mips)
    Pipeline,        // VkPipeline / GL program name
    PipelineLayout,  // VkPipelineLayout
    VertexArray,     // GL vertex array object of a pipeline
};

// ---------------------------------------------------------------------------------------------
// Device
// ---------------------------------------------------------------------------------------------
struct DeviceLimits {
    uint32_t maxTextureSize2D = 0;
    uint32_t maxTextureSize3D = 0;
    uint32_t maxTextureSizeCube = 0;
    uint32_t maxTextureArrayLayers = 0;
    // Bit n set: 2^n samples supported for colour (depth) render targets of every format the
    // engine renders to (bit 0, one sample, always).
    uint32_t colorSampleCounts = 1;
    uint32_t depthSampleCounts = 1;
    uint32_t maxColorAttachments = 0;
    uint32_t maxComputeWorkGroupInvocations = 0;
    // Work groups one dispatch may launch in x, y and z (both APIs guarantee 65535 each).
    std::array<uint32_t, 3> maxComputeWorkGroupCount = {65535, 65535, 65535};
    // Storage textures one pipeline's shaders may use (GL: image units, 8 on NVIDIA; the slot
    // numbers themselves may be any of 0 to 63 on every backend).
    uint32_t maxStorageTextures = 0;
    uint64_t maxUniformBufferRange = 0;
    uint64_t maxStorageBufferRange = 0;
    // Bytes one buffer, or one texture with all its mips, layers and samples, may take: Vulkan's
    // maxMemoryAllocationSize, at most the largest memory heap; GL's video memory
    // (NVX_gpu_memory_info), else the machine's memory. Larger requests are refused before any
    // native call (a driver may accept one and then take minutes zeroing it, as NVIDIA's GL does).
    uint64_t maxAllocationSize = 0;
    uint32_t uniformBufferOffsetAlignment = 0;
    uint32_t storageBufferOffsetAlignment = 0;
    // Viewports: width and height at most maxViewportSize; x, y, x + width and y + height within
    // viewportBounds (Vulkan's maxViewportDimensions and viewportBoundsRange, GL's
    // GL_MAX_VIEWPORT_DIMS and GL_VIEWPORT_BOUNDS_RANGE). setViewport refuses others.
    uint32_t maxViewportSize = 0;
    std::array<float, 2> viewportBounds = {0, 0};
    // Control points a tessellation patch may have (GraphicsPipelineDesc::patchControlPoints;
    // both APIs guarantee 32 where tessellation is supported; 0 without it).
    uint32_t maxTessellationPatchSize = 0;
    // Nanoseconds per unit of the timestamps resolveQueries writes (queryResults converts).
    double timestampPeriodNs = 1.0;
};

// What a format can do on a device (Device::formatCaps).
struct FormatCaps {
    bool sampled = false;
    bool linearFilter = false;  // sampled through a Linear min/mag/mip filter
    bool renderTarget = false;  // colour or depth attachment
    bool blend = false;         // a colour attachment blended into
    bool storage = false;       // storage image
    uint32_t sampleCounts = 0;  // as a render target: bit n set, 2^n samples (bit 0: one sample)
};

struct DeviceFeatures {
    bool timestamps = false;
    bool computeShaders = false;
    bool debugLabels = false;
    bool validation = false;  // Khronos validation layer / KHR_debug active
    bool memoryAliasing =
        false;            // heaps + placed textures (Vulkan); GL reuses whole objects instead
    bool window = false;  // present() shows images in a window (vulkan-glfw, gl-glfw)
    bool textureCubeArray = false;  // TextureDimension::TextureCubeArray
    // Storage images of the formats beyond the base set (RG16F, R16F, RG32F, R11G11B10F):
    // formatCaps(f).storage says so for each, and shaders may declare them.
    bool storageImageExtendedFormats = false;
    bool depthClamp = false;            // RasterState::depthClamp
    bool depthBiasClamp = false;        // RasterState::depthBiasClamp other than 0
    bool multiDrawIndirect = false;     // drawIndirect with drawCount > 1
    bool drawIndirectCount = false;     // drawIndirectCount, drawIndexedIndirectCount
    bool textureCompressionBC = false;  // Format::BC1..BC7 sampled textures
    bool occlusionQueries = false;      // QueryType::Occlusion (exact counts) and AnySamplesPassed
    bool pipelineStatistics = false;    // QueryType::PipelineStatistics
    // Shader reads of storage and uniform buffers outside the bound range give zero or values
    // from inside it, and writes there never reach memory outside it (Vulkan's robustBufferAccess
    // when DeviceCreateDesc::robustBufferAccess asks for it; a GL robust-access context).
    bool robustBufferAccess = false;
    // TextureUsage::Transient textures take memory only while a pass needs it (Vulkan's
    // LAZILY_ALLOCATED memory type); elsewhere they take memory like any texture.
    bool lazilyAllocatedMemory = false;
    // The compute / copy queue is a hardware queue of its own: its work may overlap the graphics
    // queue's (see Queues). False: it shares the graphics queue, in submission order.
    bool asyncCompute = false;
    bool asyncCopy = false;
    bool geometryShaders = false;      // GraphicsPipelineDesc::geometryShader
    bool tessellationShaders = false;  // tessControlShader, tessEvaluationShader, PatchList
};

struct DeviceInfo {
    std::string backend;     // "vulkan", "gl-egl", "gl-osmesa", "vulkan-glfw", "gl-glfw"
    std::string deviceName;  // e.g. "llvmpipe (LLVM 15.0.6, 256 bits)"
    std::string apiVersion;  // e.g. "Vulkan 1.3.230" or "OpenGL 4.5 (Core Profile) Mesa 22.3.6"
    // The driver as vulkaninfo names it: Vulkan's driverName and driverInfo (e.g. "llvmpipe",
    // "Mesa 22.3.6 (LLVM 15.0.6)"); GL's vendor string and what the context promises.
    std::string driverName;
    std::string driverInfo;
    std::string conformanceVersion;  // Vulkan: the CTS version the driver passed; GL: empty
    // "cpu", "integrated-gpu", "discrete-gpu", "virtual-gpu" or "other" (Vulkan's device type);
    // GL has none: "cpu" for a software rasterizer, else "gpu".
    std::string deviceType;
    std::string presentMode;  // windows: how frames reach the screen, e.g. "FIFO (vsync on)"
    bool softwareRasterizer = false;
    DeviceLimits limits;
    DeviceFeatures features;
    // What the driver offers, for reports (fe info --json): its extensions, sorted, and its
    // memory heaps (Vulkan; GL reports none).
    std::vector<std::string> extensions;
    struct MemoryHeap {
        uint64_t bytes = 0;
        bool deviceLocal = false;
    };
    std::vector<MemoryHeap> memoryHeaps;
};

// What a device holds now, for leak checks (tests, tools): gdi objects by kind, and the native
// objects behind buffers and textures (Vulkan: VkBuffers, VkImages and memory sub-allocations,
// staging included; GL: buffer and texture objects).
// With FE_LEAK_CHECK=1 in the environment a device, when destroyed, prints on stderr what its
// users left alive ("fe leak check: vulkan device destroyed with {buffers 1, ...}"; it frees
// them either way), so a whole program's run is leak-checked without a test harness.
struct LiveObjects {
    uint32_t buffers = 0, textures = 0, samplers = 0, shaders = 0, pipelines = 0, timers = 0,
             heaps = 0, querySets = 0;
    uint32_t nativeObjects = 0;
    friend bool operator==(const LiveObjects&, const LiveObjects&) = default;
};

using FenceValue = uint64_t;

// Device::createCommandList: the queue the list's work is submitted to (see Queues).
struct CommandListDesc {
    QueueKind queue = QueueKind::Graphics;
};
// Device::submit: what the submission waits for before it starts (see Queues). 0: nothing
// beyond its own queue's order. A fence no submit has returned yet is an Error.
struct SubmitDesc {
    FenceValue waitFor = 0;
};

// The device's pipeline cache (Device::openPipelineCache, DeviceCreateDesc::pipelineCache).
struct PipelineCacheStats {
    std::string path;          // empty: no file (pipelines are still cached in memory)
    bool loaded = false;       // the file's data was accepted
    uint64_t loadedBytes = 0;  // of backend data
    uint32_t hits = 0;         // pipelines created from cached data (where the backend can tell)
    uint32_t misses = 0;       // pipelines compiled
    std::string warning;       // why the file was ignored, or why the backend cannot cache
    // Pipelines that took the native objects of an equal pipeline the device had made, alive or
    // destroyed a short while ago (the device keeps its last 128 unused ones): nothing compiled.
    uint32_t shared = 0;
};

// Threads: every member may be called from any thread, concurrently, except present() and
// input() on windowed backends, which belong to the thread that created the device (window
// systems require it). The device serialises
// what it must: creation, destruction, transfers, submit and wait take one lock each (on GL
// they run on the thread that owns the context, which replays submitted lists in order), so
// they are safe but do not run in parallel with each other. What runs in parallel is
// recording: binding and drawing take no device lock (Vulkan takes it briefly when a
// recording starts and when a pass first uses an attachment view). Objects used by a list
// must not be destroyed while that list is being recorded or is unsubmitted (its submit
// throws Error; a call that looks the object up after its destroy throws Error at once, also
// when another thread destroys it during the call, and nothing crashes). A submit that throws
// runs none of its lists and leaves them as they were.
// Several devices may be used from several threads at once. On Mesa's software GL drivers
// (llvmpipe, softpipe) the GL devices of a process take turns (one lock they all share), since
// two of their contexts starting work at once crashed Mesa 22.3; other GL drivers run in parallel.
// Destroy command lists before their device; a list that outlives it is safe to destroy, and
// recording into it throws Error.
class Device {
public:
    virtual ~Device() = default;

    virtual const DeviceInfo& info() const = 0;
    virtual bool supportsFormat(Format format, TextureUsage usage) const = 0;
    // Everything a format can do on this device (Vulkan: its optimal-tiling features and image
    // format properties; GL: the internal-format queries). setTexture refuses a sampler that
    // filters linearly (any Linear filter, no comparison) on a format without linearFilter.
    virtual FormatCaps formatCaps(Format format) const = 0;

    // Pipeline cache: compiled pipelines kept across runs (Vulkan: VkPipelineCache data; GL:
    // program binaries), in one file keyed by backend, device, driver and engine build
    // (PipelineCacheFile.h). openPipelineCache loads `path` when it exists, before the pipelines
    // it should speed up are made; a file made elsewhere, damaged or truncated is ignored, never
    // handed to the driver, and the returned stats' warning says why (createDevice with
    // DeviceCreateDesc::pipelineCache also prints it on stderr). savePipelineCache
    // writes it (whole or not at all); the device also saves when destroyed.
    virtual PipelineCacheStats openPipelineCache(const std::string& path) = 0;
    virtual void savePipelineCache() = 0;
    virtual PipelineCacheStats pipelineCacheStats() const = 0;

    // Initial data, when given, must be exactly desc.size bytes.
    virtual BufferHandle createBuffer(const BufferDesc& desc, ByteSpan initialData = {}) = 0;
    virtual TextureHandle createTexture(const TextureDesc& desc) = 0;
    // A view of `texture` (TextureViewDesc); desc(view) describes it (its size is the base mip's).
    virtual TextureHandle createTextureView(TextureHandle texture, const TextureViewDesc& desc) = 0;
    virtual SamplerHandle createSampler(const SamplerDesc& desc) = 0;
    virtual ShaderHandle createShader(const ShaderDesc& desc) = 0;
    virtual PipelineHandle createGraphicsPipeline(const GraphicsPipelineDesc& desc) = 0;
    virtual PipelineHandle createComputePipeline(const ComputePipelineDesc& desc) = 0;
    virtual TimerHandle createTimer() = 0;
    // Heaps exist where DeviceFeatures::memoryAliasing is true; elsewhere these throw Error.
    virtual HeapHandle createHeap(const HeapDesc& desc) = 0;
    // Timestamp sets need DeviceFeatures::timestamps, the others their feature.
    virtual QuerySetHandle createQuerySet(const QuerySetDesc& desc) = 0;
    virtual MemoryRequirements textureMemoryRequirements(const TextureDesc& desc) const = 0;

    // Destruction is immediate for the caller (the handle is invalid at once) and deferred for
    // the GPU: the object's memory is released once every submission made before the call has
    // completed, without waiting (an object made and destroyed with no submission between is
    // released at once: its first commands, such as the zero fill of new memory, never run).
    // Destroying an object that a recorded, not yet submitted list uses makes that list's
    // submit throw Error; recording into that list may go on meanwhile (its memory is held
    // until the list is submitted or destroyed). The same holds for an object only bound to a
    // list (setUniformBuffer and the like before its first command) when it is destroyed.
    virtual void destroy(BufferHandle) = 0;
    virtual void destroy(TextureHandle) = 0;
    virtual void destroy(SamplerHandle) = 0;
    virtual void destroy(ShaderHandle) = 0;
    virtual void destroy(PipelineHandle) = 0;
    virtual void destroy(TimerHandle) = 0;
    virtual void destroy(HeapHandle) = 0;  // placed textures must be destroyed first
    virtual void destroy(QuerySetHandle) = 0;

    virtual const BufferDesc& desc(BufferHandle) const = 0;
    virtual const TextureDesc& desc(TextureHandle) const = 0;
    // What a shader declares, reflected when it was created (ShaderReflection.h): its bindings,
    // each uniform and storage block's size and members with their offsets (BlockMember), its
    // inputs, outputs and specialization constants. UniformBlock (UniformBlock.h) writes a
    // block's members by name from it, as a port from glUniform* needs.
    virtual const ShaderInterface& shaderInterface(ShaderHandle) const = 0;

    // Queue-ordered writes: the data is copied before the call returns (the caller may reuse
    // its memory), and the write takes effect after all work submitted before the call and
    // before all work submitted after it, as if it were a command of its own submission. So a
    // list recorded before writeBuffer and submitted after it reads the new data, and work in
    // flight never sees a half-written buffer. Blocking: on GL they return at once (the context
    // thread applies them in order); on Vulkan they wait for the work in flight (GpuOnly memory
    // is staged and copied; Upload memory is written once nothing in flight can read it).
    // Per-frame data without any wait: map() an Upload buffer, one region per frame in flight.
    virtual void writeBuffer(BufferHandle buffer, uint64_t offset, ByteSpan data) = 0;
    // One subresource: tightly packed rows, top to bottom, in the texture's format (compressed
    // formats: rows of 4x4 blocks); exactly textureByteSize(desc, at.mipLevel) bytes.
    virtual void writeTexture(TextureHandle texture, Subresource at, ByteSpan data) = 0;
    // A region of uncompressed colour texels laid out as `layout` says (its offset counts from
    // data's start); data holds at least what the layout spans. Queue-ordered like the above.
    virtual void writeTextureRegion(TextureHandle texture, const TextureRegion& region,
                                    ByteSpan data, const TexelLayout& layout = {}) = 0;
    // Blocking reads: they wait for all work submitted before the call, then copy.
    virtual std::vector<uint8_t> readBuffer(BufferHandle buffer, uint64_t offset,
                                            uint64_t size) = 0;
    // One subresource of a single-sample, uncompressed texture.
    virtual Image readTexture(TextureHandle texture, Subresource at = {}) = 0;

    // Mapped memory: the buffer's bytes in CPU address space, never blocking.
    //  - Upload buffers: a write-only pointer, persistent (the same pointer until destroy),
    //    coherent: bytes written before a submit are what the GPU reads when that work runs.
    //    Pacing is the caller's: do not overwrite a region that work in flight still reads
    //    (keep one region per frame in flight and wait on the fence of its last use).
    //  - Readback buffers: a read-only pointer whose bytes are valid once the fence of the
    //    work that wrote them (a copy into the buffer, a shader store) has completed: submit,
    //    then wait(fence) or poll isComplete(fence), then read. No staging, no extra copy.
    //  GpuOnly buffers cannot be mapped (Error).
    virtual void* map(BufferHandle buffer) = 0;

    virtual std::unique_ptr<CommandList> createCommandList(const CommandListDesc& desc) = 0;
    std::unique_ptr<CommandList> createCommandList() { return createCommandList({}); }
    // Submits lists in order as one submission to their queue (all made for one queue; an empty
    // submission goes to the graphics queue); its fence covers all of them. Each list is then
    // empty, ready to record again (while the submitted work runs).
    virtual FenceValue submit(std::span<CommandList* const> lists, const SubmitDesc& desc) = 0;
    FenceValue submit(std::span<CommandList* const> lists) { return submit(lists, {}); }
    FenceValue submit(CommandList& commands, const SubmitDesc& desc = {}) {
        CommandList* list = &commands;
        return submit(std::span<CommandList* const>(&list, 1), desc);
    }
    // Blocks until the submission with this fence (and every one before it) has completed. A
    // fence no submit has returned yet is an Error (here and in isComplete); 0 is always complete.
    virtual void wait(FenceValue fence) = 0;
    // Whether it has completed, without blocking.
    virtual bool isComplete(FenceValue fence) = 0;
    virtual void waitIdle() = 0;
    // For destructors, which must not throw: wait / waitIdle, except that a lost device has
    // nothing left to wait for.
    void waitOrLost(FenceValue fence) {
        try {
            wait(fence);
        } catch (const DeviceLostError&) {}
    }
    void waitIdleOrLost() {
        try {
            waitIdle();
        } catch (const DeviceLostError&) {}
    }

    // GPU time between beginTimer and endTimer of the last submitted use; nullopt until that
    // submission has completed (it never waits). A recording begins and ends a timer once each,
    // outside passes and secondary lists; a timer begun twice, ended unbegun, or left unended at
    // submit is an Error.
    virtual std::optional<double> timerNanoseconds(TimerHandle timer) = 0;
    // Results of queries [first, first + count) from their last submitted use, without blocking:
    // false (and `out` untouched) until every one of them has been submitted and its submission
    // has completed. `out` holds count values (4 x count for PipelineStatistics, in its order);
    // timestamps in nanoseconds, AnySamplesPassed 0 or 1.
    virtual bool queryResults(QuerySetHandle set, uint32_t first, uint32_t count,
                              std::span<uint64_t> out) = 0;

    // Messages of severity "error" from the validation layer or the GL debug output so far.
    virtual uint32_t validationErrorCount() const = 0;
    virtual LiveObjects liveObjects() const = 0;

    // Window presentation, where DeviceFeatures::window (vulkan-glfw, gl-glfw): after the work
    // submitted so far, shows `texture` (RGBA8, BGRA8 or their sRGB forms; CopySrc usage) in the
    // window, sized to it, colours unchanged, and swaps. Returns false once the user has closed the window.
    // Headless backends throw Error.
    virtual bool present(TextureHandle texture) {
        throw Error(info().backend +
                    ": no window to present to (the vulkan-glfw and gl-glfw backends have one)");
    }
    // What the window shows now, top row first, RGBA8 (tests check presentation with it).
    virtual Image readWindow() { throw Error(info().backend + ": no window to read"); }
    // The window's mouse, keys and typed text as of the last present() (headless: none).
    virtual InputState input() const { return {}; }

    // Escape hatch: the native object behind a handle id (see NativeObject); 0 when not
    // applicable. Nothing above layer 4 uses it; bench/ and interop code do.
    virtual uint64_t nativeObject(NativeObject what, uint32_t handleId = 0) const { return 0; }
};

}  // namespace fe::gdi
