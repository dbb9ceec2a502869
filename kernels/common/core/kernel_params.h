/* Each production kernel's parameter list, declared once (pbrt-v4 declares its work items once for
 * the same reason). OpenCL C 1.2 forbids pointers inside struct arguments, so a list is an X-macro:
 * LIST(P, G) names each parameter P(kind, element type, name) and each group of parameters that
 * several kernels share G(group type, member name, GROUP_LIST). Kernels expand a list into their
 * signature with CO_PARAMS(LIST); the host (runtime/backend/kernel_args.h) expands the same list
 * into a struct of named buffers and values whose bind() sets the arguments in order.
 *
 * Kinds: IN (global, read only), IO (global), UNIFORM (constant memory), LOCAL (the kernel's
 * dynamically sized local array, CO_LOCAL_PARAM in port.h) and VALUE (a scalar or struct by value). */
#ifndef COHORT_KERNEL_PARAMS_H
#define COHORT_KERNEL_PARAMS_H

#include "common/core/contract.h"

/* ---- Expansion into a parameter list ----------------------------------------------------------
 * Every parameter expands to "declaration,", and CO_PARAMS ends the list with one unused value,
 * co_params_end (0), which takes the last comma: NVIDIA's OpenCL C compiler has no variadic macros,
 * so a leading comma cannot be dropped instead. A list is shared by kernels (and helpers) that read
 * different parts of it, so on the host a parameter may go unused without a warning. */
#if defined(__OPENCL_VERSION__) || defined(__CUDACC__)
#define CO_MAYBE_UNUSED
#else
#define CO_MAYBE_UNUSED [[maybe_unused]]
#endif
#define CO_PARAM(kind, T, name) CO_PARAM_##kind(T, name)
#define CO_PARAM_IN(T, name) CO_MAYBE_UNUSED CO_GLOBAL const T* name,
#define CO_PARAM_FEATURE_IN(T, name) CO_PARAM_IN(T, name)
#define CO_PARAM_FEATURE_ABSENT(T, name) /* the program is built without the feature */
#define CO_PARAM_IO(T, name) CO_MAYBE_UNUSED CO_GLOBAL T* name,
#define CO_PARAM_UNIFORM(T, name) CO_MAYBE_UNUSED CO_CONSTANT T* name,
#define CO_PARAM_VALUE(T, name) CO_MAYBE_UNUSED T name,
#if defined(__CUDACC__)
#define CO_PARAM_LOCAL(T, name) /* the launch's dynamic shared memory: CO_LOCAL_BIND */
#else
#define CO_PARAM_LOCAL(T, name) CO_LOCAL T* name,
#endif
#define CO_PARAM_GROUP(Group, member, LIST) LIST(CO_PARAM, CO_PARAM_GROUP_NESTED)
#define CO_PARAM_GROUP_NESTED(Group, member, LIST) LIST(CO_PARAM, CO_PARAM_GROUP_NESTED)
#define CO_PARAMS(LIST) LIST(CO_PARAM, CO_PARAM_GROUP) CO_MAYBE_UNUSED uint32_t co_params_end

/* The names of a list, as the arguments of a call to a helper declared with CO_PARAMS(LIST) (a
 * list without a LOCAL parameter: CUDA has none to pass). */
#define CO_ARG(kind, T, name) CO_ARG_##kind(name)
#define CO_ARG_IN(name) name,
#define CO_ARG_IO(name) name,
#define CO_ARG_UNIFORM(name) name,
#define CO_ARG_VALUE(name) name,
#define CO_ARG_LOCAL(name) name,
#define CO_ARG_FEATURE_IN(name) name,
#define CO_ARG_FEATURE_ABSENT(name)
#define CO_ARG_GROUP(Group, member, LIST) LIST(CO_ARG, CO_ARG_GROUP_NESTED)
#define CO_ARG_GROUP_NESTED(Group, member, LIST) LIST(CO_ARG, CO_ARG_GROUP_NESTED)
#define CO_ARGS(LIST) LIST(CO_ARG, CO_ARG_GROUP) 0u

/* ---- Groups -------------------------------------------------------------------------------- */

/* A feature's table that only the programs built for it take: kind FEATURE_IN with the feature's
 * option (an IN parameter), FEATURE_ABSENT without it (no parameter, no argument), so the programs
 * of a scene without the feature have the parameter lists they had before it. The host's argument
 * structs have the field either way and bind it only when it holds a buffer (kernel_args.h). */
#if defined(COHORT_FEATURE_CLEARCOAT)
#define SCENE_CLEARCOAT_BUFFERS(P) P(FEATURE_IN, MaterialCoat, material_coats)
#else
#define SCENE_CLEARCOAT_BUFFERS(P) P(FEATURE_ABSENT, MaterialCoat, material_coats)
#endif
#if defined(COHORT_FEATURE_SHEEN)
#define SCENE_SHEEN_BUFFERS(P) P(FEATURE_IN, MaterialSheen, material_sheen)
#else
#define SCENE_SHEEN_BUFFERS(P) P(FEATURE_ABSENT, MaterialSheen, material_sheen)
#endif
#if defined(COHORT_FEATURE_SPECULAR)
#define SCENE_SPECULAR_BUFFERS(P) P(FEATURE_IN, MaterialSpecular, material_specular)
#else
#define SCENE_SPECULAR_BUFFERS(P) P(FEATURE_ABSENT, MaterialSpecular, material_specular)
#endif

/* The scene's buffers (scene_view.h makes them a SceneView with the RenderParams). */
#define SCENE_BUFFERS(P, G)                                                                                   \
  P(IN, KdNode, nodes) P(IN, uint32_t, leaf_triangles) P(IN, Triangle, triangles)                            \
  P(IN, uint32_t, triangle_material) P(IN, Material, materials) P(IN, EmitterEntry, emitters)                \
  P(IN, TriangleUv, triangle_uvs) P(IN, TextureDesc, textures) P(IN, uint32_t, texels)                       \
  P(IN, TriangleColor, triangle_colors) P(IN, TriangleFrame, triangle_frames) P(IN, co_float4, env_texels) P(IN, float, env_tables)               \
  P(IN, PunctualLight, punctual_lights) SCENE_CLEARCOAT_BUFFERS(P) SCENE_SHEEN_BUFFERS(P) \
  SCENE_SPECULAR_BUFFERS(P)

/* What every rendering kernel takes: the render's parameters and the scene. */
#define SCENE_PARAMS(P, G) P(UNIFORM, RenderParams, params) G(SceneBuffers, scene, SCENE_BUFFERS)

/* The path slots of the wavefront pool, structure of arrays: one path_<buffer> per entry of
 * PATH_SLOT (path_slot.h), in its order. */
#define CO_SLOT_PARAM(P, buf, T, N, state, f, wf, what) P(IO, CO_SLOT_TYPE(T, N), path_##buf)
#define PATH_BUFFERS(P, G) PATH_SLOT(CO_SLOT_PARAM, P)

/* The shadow ray each shaded path may queue, by slot, and the queue of slots that have one. */
#define SHADOW_BUFFERS(P, G)                                                                                  \
  P(IO, co_float4, shadow_org) P(IO, co_float4, shadow_dir) P(IO, co_float4, shadow_contribution)            \
  P(IO, uint32_t, shadow_queue)

/* ---- naive_kernel.h ------------------------------------------------------------------------- */
#define RENDER_NAIVE_PARAMS(P, G)                                                                             \
  SCENE_PARAMS(P, G) P(IO, co_float4, film) P(IO, uint32_t, counters) P(IO, uint32_t, dropped_samples)      \
  P(IN, uint32_t, pixel_list)

/* ---- aov_kernel.h: first-hit albedo, normal and depth, summed per pixel ------------------------ */
/* aov_samples: each pixel's sample count (adaptive sampling: its own; else the image's) */
#define RENDER_AOV_PARAMS(P, G)                                                                               \
  SCENE_PARAMS(P, G) P(IO, co_float4, aov_albedo) P(IO, co_float4, aov_normal) P(IN, uint32_t, aov_samples)

/* ---- wavefront_kernels.h --------------------------------------------------------------------
 * `queue` and `use_queue`: with stream compaction a launch index stands for queue[index], else for
 * the slot itself; `count` is the launch's size, and with the queue only its first
 * counters[COUNTER_QUEUE] indices work (launch_count). `pixel_list`: the pixels of an adaptive
 * pass (pass_pixel in pathtrace.h), here and in render_naive. */
#define WF_GENERATE_PARAMS(P, G)                                                                              \
  P(UNIFORM, RenderParams, params) G(PathBuffers, path, PATH_BUFFERS) P(IO, uint32_t, counters)              \
  P(IO, uint32_t, queue) P(VALUE, uint32_t, use_queue) P(VALUE, uint32_t, slot_count) P(VALUE, uint32_t, item_end)      \
  P(VALUE, uint32_t, regenerate) P(IN, uint32_t, pixel_list)

#define WF_EXTEND_PARAMS(P, G)                                                                                \
  SCENE_PARAMS(P, G) G(PathBuffers, path, PATH_BUFFERS) P(IO, HitOut, hits) P(IN, uint32_t, queue)           \
  P(VALUE, uint32_t, use_queue) P(VALUE, uint32_t, count) P(IO, uint32_t, steps) P(IN, uint32_t, counters)

#define WF_SHADE_PARAMS(P, G)                                                                                 \
  SCENE_PARAMS(P, G) G(PathBuffers, path, PATH_BUFFERS) P(IN, HitOut, hits) P(IN, uint32_t, queue)           \
  P(VALUE, uint32_t, use_queue) P(VALUE, uint32_t, count) G(ShadowBuffers, shadow, SHADOW_BUFFERS)           \
  P(IO, uint32_t, counters) P(IN, uint32_t, pixel_list)

#define WF_SHADOW_PARAMS(P, G)                                                                                \
  SCENE_PARAMS(P, G) P(IO, co_float4, path_radiance) G(ShadowBuffers, shadow, SHADOW_BUFFERS)                \
  P(IN, uint32_t, counters) P(IO, uint32_t, steps)

#define WF_FINISH_PARAMS(P, G)                                                                                \
  G(PathBuffers, path, PATH_BUFFERS) P(IO, co_float4, results) P(IO, uint32_t, counters) P(IO, uint32_t, queue) \
  P(VALUE, uint32_t, use_queue) P(VALUE, uint32_t, slot_count)

#define WF_ACCUMULATE_PARAMS(P, G)                                                                            \
  P(UNIFORM, RenderParams, params) P(IN, co_float4, results) P(IO, co_float4, film) P(IO, uint32_t, dropped_samples) \
  P(IN, uint32_t, pixel_list)

#define WF_SIMD_EFFICIENCY_PARAMS(P, G)                                                                       \
  P(IN, uint32_t, steps) P(VALUE, uint32_t, count) P(IO, uint32_t, counters) P(VALUE, uint32_t, use_queue)

/* one work item: the bounce's row of figures, and the per-bounce counters zeroed for wf_finish */
#define WF_END_BOUNCE_PARAMS(P, G) P(IO, uint32_t, counters) P(VALUE, uint32_t, bounce)

#define WF_SHADOW_MAX_STEPS_PARAMS(P, G) P(IN, uint32_t, steps) P(IO, uint32_t, counters)

/* ---- pth_kernels.h ----------------------------------------------------------------------------
 * The walk reads the path slots of `queue` (or all), writes (code, slot) pairs for the sort and
 * the traversal state it stopped at; the resume continues in the sorted order. `hits` holds each
 * path's previous hit (its distance is the two-point key's estimate) until the walk or the resume
 * writes this bounce's. The two walk kernels differ only in the width of their keys. */
#define PTH_WALK_PARAMS(P, G)                                                                                 \
  SCENE_PARAMS(P, G) P(IN, co_float4, path_org) P(IN, co_float4, path_dir) P(IN, uint32_t, path_item)        \
  P(IN, uint32_t, path_segment) P(IN, uint32_t, path_status) P(IN, uint32_t, queue)                          \
  P(VALUE, uint32_t, use_queue) P(VALUE, uint32_t, count) P(VALUE, uint32_t, subtree_nodes)                  \
  P(UNIFORM, CodeParams, code_params) P(IN, float, origin_bounds) P(IO, uint32_t, values)                    \
  P(IO, TraversalState, traversal) P(IO, SavedStackEntry, traversal_stack) P(VALUE, uint32_t, stack_stride)  \
  P(IO, HitOut, hits) P(IN, uint32_t, counters)

/* the top of the tree the walk keeps in local memory: the 4-wide BVH's nodes or the KD-tree's (the
 * host's argument is a byte count either way) */
#if defined(COHORT_ACCEL_BVH4)
#define PTH_TOP_NODE Bvh4Node
#else
#define PTH_TOP_NODE KdNode
#endif
#define PTH_WALK_AND_CODE_PARAMS(P, G) G(PthWalk, walk, PTH_WALK_PARAMS) P(LOCAL, PTH_TOP_NODE, subtree) P(IO, uint64_t, keys)
#define PTH_WALK_AND_CODE32_PARAMS(P, G)                                                                      \
  G(PthWalk, walk, PTH_WALK_PARAMS) P(LOCAL, PTH_TOP_NODE, subtree) P(IO, uint32_t, keys)

/* pth_gather (--sort-payload gather): ray and saved state of sorted item i to position i */
#define PTH_GATHER_PARAMS(P, G)                                                                               \
  P(IN, uint32_t, sorted_slots) P(VALUE, uint32_t, count) P(IN, uint32_t, counters) P(VALUE, uint32_t, use_queue) \
  P(IN, co_float4, path_org) P(IN, co_float4, path_dir) P(IN, TraversalState, traversal)                     \
  P(IN, SavedStackEntry, traversal_stack) P(VALUE, uint32_t, stack_stride) P(IO, co_float4, sorted_org)        \
  P(IO, co_float4, sorted_dir) P(IO, TraversalState, sorted_traversal) P(IO, SavedStackEntry, sorted_stack)

/* pth_resume and pth_resume_speculative: `gathered` 1 reads ray and state at the sorted position
 * (path_org, path_dir, traversal and traversal_stack are then pth_gather's sorted copies) */
#define PTH_RESUME_PARAMS(P, G)                                                                               \
  SCENE_PARAMS(P, G) P(IN, co_float4, path_org) P(IN, co_float4, path_dir) P(IN, uint32_t, sorted_slots)     \
  P(VALUE, uint32_t, count) P(IN, TraversalState, traversal) P(IN, SavedStackEntry, traversal_stack)         \
  P(VALUE, uint32_t, stack_stride) P(IO, HitOut, hits) P(IO, uint32_t, steps) P(IN, uint32_t, counters)      \
  P(VALUE, uint32_t, use_queue) P(VALUE, uint32_t, gathered)

/* ---- trace_kernels.h: traversal only, for a buffer of rays -------------------------------------- */
#define TRACE_TREE_PARAMS(P, G)                                                                               \
  P(IN, KdNode, nodes) P(IN, uint32_t, leaf_triangles) P(IN, Triangle, triangles) P(VALUE, co_float4, scene_min) \
  P(VALUE, co_float4, scene_max)

#define TRACE_RAYS_PARAMS(P, G)                                                                               \
  G(TraceTree, tree, TRACE_TREE_PARAMS) P(IN, RayIn, rays) P(IO, HitOut, hits) P(VALUE, uint32_t, count)     \
  P(VALUE, uint32_t, any_hit)

#define TRACE_RAYS_STEPS_PARAMS(P, G) TRACE_RAYS_PARAMS(P, G) P(IO, uint32_t, steps)

#define TRACE_RAYS_PTH_PARAMS(P, G)                                                                           \
  G(TraceTree, tree, TRACE_TREE_PARAMS) P(IN, RayIn, rays) P(IO, HitOut, hits) P(VALUE, uint32_t, count)     \
  P(LOCAL, KdNode, subtree) P(VALUE, uint32_t, subtree_nodes) P(VALUE, uint32_t, levels)                     \
  P(IO, uint32_t, pth_bits)

#define TRACE_RAYS_SPECULATIVE_PARAMS(P, G)                                                                   \
  G(TraceTree, tree, TRACE_TREE_PARAMS) P(IN, RayIn, rays) P(IO, HitOut, hits) P(VALUE, uint32_t, count)     \
  P(IO, uint32_t, steps)

/* ---- film_kernels.h ------------------------------------------------------------------------- */
#define FILM_ADD_PARAMS(P, G)                                                                                 \
  P(IO, co_float4, image) P(IN, co_float4, pass) P(VALUE, uint32_t, pixels) P(IO, co_float4, group_sums)     \
  P(IN, uint32_t, dropped) P(VALUE, uint32_t, groups)

#endif
