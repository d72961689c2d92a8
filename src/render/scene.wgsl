// ArmLab's scene shader: lit, instanced meshes and unlit coloured lines.
// Colours arrive linear; shading is linear; the output is encoded to sRGB here because the
// target is a plain Rgba8Unorm texture (what egui samples as gamma-space colour).

struct Globals {
    view_proj: mat4x4<f32>,
    // xyz: direction the key light travels; w unused.
    light_dir: vec4<f32>,
    // xyz: eye position.
    eye: vec4<f32>,
};

@group(0) @binding(0) var<uniform> globals: Globals;

fn srgb_from_linear(c: vec3<f32>) -> vec3<f32> {
    let lo = c * 12.92;
    let hi = 1.055 * pow(max(c, vec3<f32>(0.0)), vec3<f32>(1.0 / 2.4)) - 0.055;
    return select(hi, lo, c <= vec3<f32>(0.0031308));
}

struct MeshIn {
    @location(0) position: vec3<f32>,
    @location(1) normal: vec3<f32>,
    @location(2) m0: vec4<f32>,
    @location(3) m1: vec4<f32>,
    @location(4) m2: vec4<f32>,
    @location(5) m3: vec4<f32>,
    @location(6) color: vec4<f32>,
};

struct MeshOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) normal: vec3<f32>,
    @location(1) color: vec4<f32>,
    @location(2) world: vec3<f32>,
};

@vertex
fn vs_mesh(v: MeshIn) -> MeshOut {
    let model = mat4x4<f32>(v.m0, v.m1, v.m2, v.m3);
    // Normals transform by the inverse transpose of the model's 3×3 part, M⁻ᵀ = cof(M) / det M.
    // The cofactor matrix (columns b×c, c×a, a×b for M's columns a, b, c) has the same
    // directions: the length goes in the fragment's normalize, and the sign in its
    // two-sided test. It needs no division, so a flat (zero-scale) part keeps the normal
    // of its face.
    let a = v.m0.xyz;
    let b = v.m1.xyz;
    let c = v.m2.xyz;
    let normal_matrix = mat3x3<f32>(cross(b, c), cross(c, a), cross(a, b));
    let world = model * vec4<f32>(v.position, 1.0);
    var out: MeshOut;
    out.clip = globals.view_proj * world;
    out.normal = normal_matrix * v.normal;
    out.color = v.color;
    out.world = world.xyz;
    return out;
}

@fragment
fn fs_mesh(v: MeshOut) -> @location(0) vec4<f32> {
    var n = normalize(v.normal);
    let to_eye = normalize(globals.eye.xyz - v.world);
    // Two-sided: light the face that looks at the camera.
    if (dot(n, to_eye) < 0.0) {
        n = -n;
    }
    let key = max(dot(n, -globals.light_dir.xyz), 0.0);
    let fill = max(dot(n, to_eye), 0.0);
    let half_vec = normalize(-globals.light_dir.xyz + to_eye);
    let spec = pow(max(dot(n, half_vec), 0.0), 32.0) * 0.25;
    let shade = 0.28 + 0.55 * key + 0.22 * fill;
    let lit = min(v.color.rgb * shade + vec3<f32>(spec), vec3<f32>(1.0));
    return vec4<f32>(srgb_from_linear(lit), v.color.a);
}

struct LineIn {
    @location(0) position: vec3<f32>,
    @location(1) color: vec4<f32>,
};

struct LineOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) color: vec4<f32>,
};

@vertex
fn vs_line(v: LineIn) -> LineOut {
    var out: LineOut;
    out.clip = globals.view_proj * vec4<f32>(v.position, 1.0);
    out.color = v.color;
    return out;
}

@fragment
fn fs_line(v: LineOut) -> @location(0) vec4<f32> {
    return vec4<f32>(srgb_from_linear(v.color.rgb), v.color.a);
}
