// Stage `objects`: the scene's spheres and boxes, lit by the sun and the sky, drawn three
// ways (seed 000 §2.2, §5.2):
// - vs_main / fs_main: the main view;
// - vs_reflect / fs_reflect: mirrored in the plane y = 0 and seen from the eye, the parts
//   above the water only — the reflection map (alpha = coverage);
// - vs_refract / fs_refract: the parts under the water, scaled along y by 1/η (the apparent
//   depth of a flat interface seen from above), fogged by eq. 4 (seed 001's eq. 7 with the
//   colour of its eq. 8 under shading `chiu`) — the refraction map.
// Under the water they are lit by the downwelling light: the sun through the surface, shadowed
// by the casters above the water and by the floor's relief (shared/floor.wgsl), and the sky.
// CPU mirror: crates/ocean-cpu/src/shaders/objects.rs.

// #import shared/frame.wgsl
// #import shared/optics.wgsl
// #import shared/floor.wgsl

@group(0) @binding(0) var<uniform> frame: FrameUniforms;
// (disp_x, height, disp_z, jacobian): the wave height under a fragment, for the exact-height
// clipping of shading `chiu` (§3.5.1).
@group(0) @binding(1) var displacement: texture_2d<f32>;
@group(0) @binding(2) var wrap_linear: sampler;
// The sun's shadow map and the sea floor's relief: the sun reaching what lies under the water
// (shared/floor.wgsl).
@group(0) @binding(3) var shadow_map: texture_2d<f32>;
@group(0) @binding(4) var floor_map: texture_2d<f32>;
@group(0) @binding(5) var clamp_linear: sampler;

struct ObjectVertex {
    @location(0) position: vec3<f32>,
    @location(1) normal: vec3<f32>,
    @location(2) color: vec3<f32>,
}

struct VertexOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) normal: vec3<f32>,
    @location(1) color: vec3<f32>,
    // Camera-relative position of the point as drawn (mirrored or scaled).
    @location(2) rel: vec3<f32>,
    // Height of the original point above the mean sea plane, m.
    @location(3) world_y: f32,
}

const INV_PI: f32 = 0.31830988618;

// Lambert: albedo/π · (E_sun cos θ·sun + π·ambient), `sun` the share of the sun that reaches
// the point (1 above the water, sun_reaches under it).
fn shade(normal: vec3<f32>, color: vec3<f32>, sun: f32) -> vec3<f32> {
    let n = unit(normal);
    let cos_sun = max(dot3(n, frame.sun.direction), 0.0) * (frame.sun.lit * sun);
    let direct = frame.sun.radiance * (cos_sun * INV_PI);
    return color * (direct + frame.ambient.sky);
}

@vertex
fn vs_main(v: ObjectVertex) -> VertexOut {
    var out: VertexOut;
    out.clip = transform_point(frame.view.view_proj, v.position);
    out.normal = v.normal;
    out.color = v.color;
    out.rel = v.position;
    out.world_y = v.position.y + frame.view.eye_height;
    return out;
}

// The main view's colour at a fragment.
fn shade_main(in: VertexOut) -> vec4<f32> {
    return vec4<f32>(shade(in.normal, in.color, sun_reaches(in.rel, in.world_y)), 1.0);
}

@fragment
fn fs_main(in: VertexOut) -> @location(0) vec4<f32> {
    return shade_main(in);
}

@vertex
fn vs_reflect(v: ObjectVertex) -> VertexOut {
    // World y → −y; camera-relative: y_rel → −y_rel − 2·eye_height.
    let mirrored = vec3<f32>(v.position.x, -v.position.y - 2.0 * frame.view.eye_height, v.position.z);
    var out: VertexOut;
    out.clip = transform_point(frame.view.view_proj, mirrored);
    out.normal = vec3<f32>(v.normal.x, -v.normal.y, v.normal.z);
    out.color = v.color;
    out.rel = mirrored;
    out.world_y = v.position.y + frame.view.eye_height;
    return out;
}

// The water's height (m) under the camera-relative point `rel` where the maps clip the objects:
// shading `chiu` clips at the wave height there (seed 001 §3.5.1, Fig. 4: the displacement
// map's height at the point's (x, z), as the water's vertices sample it; its horizontal
// displacement is not inverted), every other shading at the plane y = 0.
fn clip_height(rel: vec3<f32>) -> f32 {
    if (frame.chiu.clip_waves == 0.0) {
        return 0.0;
    }
    let pos = vec2<f32>(rel.x, rel.z) - frame.tiling.mesh_offset;
    let uv = (pos + frame.tiling.displacement_origin) * frame.tiling.inv_displacement_size + frame.tiling.displacement_half_texel;
    return textureSampleLevel(displacement, wrap_linear, uv, 0.0).y * frame.passes.waves;
}

// Only what is above the water is reflected.
fn reflect_discards(in: VertexOut) -> bool {
    return in.world_y < clip_height(in.rel);
}

@fragment
fn fs_reflect(in: VertexOut) -> @location(0) vec4<f32> {
    if (reflect_discards(in)) {
        discard;
    }
    return shade_reflect(in);
}

// The reflection map's colour at a fragment that is kept.
fn shade_reflect(in: VertexOut) -> vec4<f32> {
    // The mirrored normal lit by the mirrored sun is the original normal lit by the sun.
    let n = vec3<f32>(in.normal.x, -in.normal.y, in.normal.z);
    return vec4<f32>(shade(n, in.color, 1.0), 1.0);
}

@vertex
fn vs_refract(v: ObjectVertex) -> VertexOut {
    // World y → y/η (apparent depth); camera-relative: y_rel → (y_rel + eye_height)/η − eye.
    let world_y = v.position.y + frame.view.eye_height;
    let scaled = vec3<f32>(v.position.x, world_y * frame.water.inv_eta - frame.view.eye_height, v.position.z);
    var out: VertexOut;
    out.clip = transform_point(frame.view.view_proj, scaled);
    out.normal = v.normal;
    out.color = v.color;
    out.rel = scaled;
    out.world_y = world_y;
    return out;
}

// Only what is under the water is seen through it.
fn refract_discards(in: VertexOut) -> bool {
    return in.world_y > clip_height(in.rel);
}

@fragment
fn fs_refract(in: VertexOut) -> @location(0) vec4<f32> {
    if (refract_discards(in)) {
        discard;
    }
    return shade_refract(in);
}

// The refraction map's colour at a fragment that is kept.
fn shade_refract(in: VertexOut) -> vec4<f32> {
    // Eq. 4: C = α(d)·C_deep + (1 − α(d))·C_obj, α = 1 − e^{−K d}, d the path length in the
    // water from the (apparent) point towards the eye: the part of the segment below y = 0.
    // A point between the plane and the wave above it (shading `chiu`'s clipping) is at the
    // surface: no path in the water, the full light.
    let depth_below = max(-(in.rel.y + frame.view.eye_height), 0.0);
    let height_above = max(frame.view.eye_height, 0.0);
    let dist = sqrt(dot3(in.rel, in.rel));
    let d = dist * (depth_below / (depth_below + height_above));
    let fog = 1.0 - exp(-frame.water.extinction_per_m * d);
    // The light reaching the object is the downwelling irradiance at its depth, which falls
    // as e^{−K z} (K is the diffuse extinction coefficient, §4.3).
    // The sun at the point itself, not at its apparent (scaled) position.
    let at = vec3<f32>(in.rel.x, in.world_y - frame.view.eye_height, in.rel.z);
    let sun = sun_reaches(at, in.world_y);
    let obj = shade(in.normal, in.color, sun) * exp(-frame.water.extinction_per_m * max(-in.world_y, 0.0));
    // The water's colour at the object's depth: `hu`'s constant, or eq. 8 (shading `chiu`,
    // whose eq. 7 is this same blend with atten = K).
    return vec4<f32>(water_volume_colour(-in.world_y) * fog + obj * (1.0 - fog), 1.0);
}

// The compute path (ocean-gpu's shading_path): the raster pass writes the visibility buffer,
// the last passing fragment's interpolated inputs (each f32 exactly) and a coverage flag
// (c.w: 1, 0 where nothing was drawn); a compute pass shades it at the pixel centre. The
// discards stay in the raster pass, so the depth each pass leaves is the fragment path's.
struct VisibilityOut {
    @location(0) a: vec4<f32>,
    @location(1) b: vec4<f32>,
    @location(2) c: vec4<f32>,
}

fn visibility(in: VertexOut) -> VisibilityOut {
    return VisibilityOut(
        vec4<f32>(in.normal, in.world_y),
        vec4<f32>(in.color, 0.0),
        vec4<f32>(in.rel, 1.0),
    );
}

@fragment
fn fs_visibility_main(in: VertexOut) -> VisibilityOut {
    return visibility(in);
}

@fragment
fn fs_visibility_reflect(in: VertexOut) -> VisibilityOut {
    if (reflect_discards(in)) {
        discard;
    }
    return visibility(in);
}

@fragment
fn fs_visibility_refract(in: VertexOut) -> VisibilityOut {
    if (refract_discards(in)) {
        discard;
    }
    return visibility(in);
}

@group(1) @binding(0) var vis_a: texture_2d<f32>;
@group(1) @binding(1) var vis_b: texture_2d<f32>;
@group(1) @binding(2) var vis_c: texture_2d<f32>;
// The pass's colour target: the HDR frame, the reflection or the refraction map. ocean-gpu
// makes the rgba16float variant by replacing this one declaration.
@group(1) @binding(3) var target_frame: texture_storage_2d<rgba32float, write>;

// The fragment a covered pixel's visibility buffer holds (None: `covered` false).
struct Visible {
    covered: bool,
    in: VertexOut,
}

// Whether the invocation's pixel lies in the target (each entry point asks first).
fn in_target(id: vec3<u32>) -> bool {
    let size = textureDimensions(target_frame);
    return id.x < size.x && id.y < size.y;
}

fn visible(id: vec3<u32>) -> Visible {
    var v: Visible;
    v.covered = false;
    let p = vec2<i32>(id.xy);
    let c = textureLoad(vis_c, p, 0);
    if (c.w == 0.0) {
        return v;
    }
    let a = textureLoad(vis_a, p, 0);
    let b = textureLoad(vis_b, p, 0);
    v.covered = true;
    v.in.clip = vec4<f32>(vec2<f32>(id.xy) + vec2<f32>(0.5), 0.0, 1.0);
    v.in.normal = a.xyz;
    v.in.world_y = a.w;
    v.in.color = b.xyz;
    v.in.rel = c.xyz;
    return v;
}

@compute @workgroup_size(8, 8, 1)
fn cs_shade_main(@builtin(global_invocation_id) id: vec3<u32>) {
    if (!in_target(id)) {
        return;
    }
    let v = visible(id);
    if (v.covered) {
        textureStore(target_frame, vec2<i32>(id.xy), shade_main(v.in));
    }
}

// The maps' shading stores their clear colour, 0, where nothing was drawn (alpha = coverage),
// so the map needs no clear pass of its own.
@compute @workgroup_size(8, 8, 1)
fn cs_shade_reflect(@builtin(global_invocation_id) id: vec3<u32>) {
    if (!in_target(id)) {
        return;
    }
    let v = visible(id);
    var c = vec4<f32>(0.0);
    if (v.covered) {
        c = shade_reflect(v.in);
    }
    textureStore(target_frame, vec2<i32>(id.xy), c);
}

@compute @workgroup_size(8, 8, 1)
fn cs_shade_refract(@builtin(global_invocation_id) id: vec3<u32>) {
    if (!in_target(id)) {
        return;
    }
    let v = visible(id);
    var c = vec4<f32>(0.0);
    if (v.covered) {
        c = shade_refract(v.in);
    }
    textureStore(target_frame, vec2<i32>(id.xy), c);
}
