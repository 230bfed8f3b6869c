// Stage 2, the projected domain (§4.1, steps 1-2 and the LOD paragraph): core/projected_domain.cc
// and ProjectorRays::footprint (core/projector.cc), one invocation per vertex (i, j) of the
// row pitch, padding included. Rays are recomputed for the four neighbours, as on the CPU.
// On a planet (planet.enabled) the footprint is core/planet_domain.cc's instead: the ray's near
// hit with the grid sphere (theta_true), blended into equal angles (theta_eq), as an arc
// offset (docs/planet.md).
layout(local_size_x = RELIEF_GROUP_SIZE) in;

layout(std430, binding = RELIEF_BINDING_PARAMS) readonly buffer DomainParamsBlock {
  DomainParams domain;
};
// DomainRows: descent, x0 and step_x, height + 2 values each (rows -1 .. height), one after
// the other.
layout(std430, binding = RELIEF_BINDING_ROWS) readonly buffer DomainRowsBlock {
  float domain_rows[];
};
layout(std430, binding = RELIEF_BINDING_PLANET) readonly buffer PlanetParamsBlock {
  PlanetParams planet;
};
layout(std430, binding = RELIEF_BINDING_DX) writeonly buffer DxBlock { float out_dx[]; };
layout(std430, binding = RELIEF_BINDING_DZ) writeonly buffer DzBlock { float out_dz[]; };
layout(std430, binding = RELIEF_BINDING_SIGMA) writeonly buffer SigmaBlock { float out_sigma[]; };
layout(std430, binding = RELIEF_BINDING_NU) writeonly buffer NuBlock { float out_nu[]; };
layout(std430, binding = RELIEF_BINDING_VALID) writeonly buffer ValidBlock { uint out_valid[]; };

// The work group's valid bytes, four to a word: a row's pitch is a multiple of 16 and a work
// group starts at a multiple of its size, so its words are whole words of the stream.
shared uint valid_words[RELIEF_GROUP_SIZE / 4];

struct Row {
  float descent, x0, step_x;
};

Row domain_row(int j) {
  const int rows = domain.height + 2;
  return Row(domain_rows[j + 1], domain_rows[rows + j + 1], domain_rows[2 * rows + j + 1]);
}

struct Footprint {
  float x, z;
  bool valid;
};

// planet_footprint (core/planet_domain.cc) of the ray through image point (x, y): the arc
// offset of its remapped central angle theta; invalid beyond theta_h, or where the ray misses
// the grid sphere while b = 0.
Footprint planet_footprint(float x, float y, float descent) {
  Footprint f = Footprint(0.0, 0.0, false);
  // The projector has no roll: x does not change ray.y (projector.h).
  precise float ray_x = domain.rays.fx + x * domain.rays.rx + y * domain.rays.ux;
  precise float ray_z = domain.rays.fz + x * domain.rays.rz + y * domain.rays.uz;
  precise float horizontal = square_root(ray_x * ray_x + ray_z * ray_z);
  precise float length = square_root(horizontal * horizontal + descent * descent);
  if (!(length > 0.0)) {
    return f;  // the division's domain below; never for a projector ray
  }
  precise float cos_a = divide(descent, length);
  precise float sin_a = divide(horizontal, length);
  precise float dc = planet.center_distance * cos_a;
  precise float disc = dc * dc - planet.grid_c;
  const bool hit = cos_a > 0.0 && disc >= 0.0;
  precise float theta_true = planet.theta_limb;
  if (hit) {
    // Domain: dc > 0 and c > 0, so the denominator is positive.
    precise float t = divide(planet.grid_c, dc + square_root(disc));
    precise float along = t * sin_a;
    precise float across = planet.center_distance - t * cos_a;
    theta_true = atan2_det(along, across);
  }
  precise float alpha = atan2_det(horizontal, descent);
  precise float theta_eq = planet.theta_lo + planet.eq_slope * (alpha - planet.alpha_lo);
  precise float blended = planet.one_minus_blend * theta_true + planet.blend * theta_eq;
  precise float theta = 0.0 < blended ? blended : 0.0;  // std::max(0, blended)
  if (!(theta <= planet.theta_h) || (!hit && !(planet.blend > 0.0))) {
    return f;
  }
  f.valid = true;
  // Straight down the direction is undefined and theta is 0: (0, 0). Domain: horizontal > 0.
  if (horizontal > 0.0) {
    precise float scale = divide(planet.radius * theta, horizontal);
    f.x = scale * ray_x;
    f.z = scale * ray_z;
  }
  return f;
}

// ProjectorRays::footprint at image point (x0 + i step_x, y0 + j step_y), gated by
// terrain_visible as the CPU's `&&` gates it (and, on a planet, by planet.visible).
Footprint footprint(int i, int j, Row r) {
  Footprint f = Footprint(0.0, 0.0, false);
  if (domain.terrain_visible == 0) {
    return f;
  }
  precise float x = r.x0 + float(i) * r.step_x;
  precise float y = domain.y0 + float(j) * domain.step_y;
  if (planet.enabled != 0) {
    if (planet.visible == 0) {
      return f;
    }
    return planet_footprint(x, y, r.descent);
  }
  precise float ray_x = domain.rays.fx + x * domain.rays.rx + y * domain.rays.ux;
  precise float ray_z = domain.rays.fz + x * domain.rays.rz + y * domain.rays.uz;
  precise float horizontal_sq = ray_x * ray_x + ray_z * ray_z;
  // The division's domain: descent > 0 and descent^2 above kMinRayDescent^2 of the ray's
  // squared length.
  precise float descent_sq = r.descent * r.descent;
  precise float min_descent_sq = RELIEF_MIN_RAY_DESCENT * RELIEF_MIN_RAY_DESCENT;
  precise float bound = min_descent_sq * (horizontal_sq + descent_sq);
  if (!(r.descent > 0.0) || descent_sq <= bound) {
    return f;
  }
  precise float scale = divide(domain.rays.height_above_plane, r.descent);
  precise float px = scale * ray_x;
  precise float pz = scale * ray_z;
  precise float distance_sq = px * px + pz * pz;
  if (!(distance_sq <= domain.rays.max_distance_sq)) {
    return f;
  }
  f = Footprint(px, pz, true);
  return f;
}

float distance_sq(Footprint a, Footprint b) {
  precise float ex = a.x - b.x;
  precise float ez = a.z - b.z;
  precise float d = ex * ex + ez * ez;
  return d;
}

// Squared spacing along one grid axis: central, one-sided, or 0.
float axis_spacing_sq(Footprint minus, Footprint centre, Footprint plus) {
  precise float s = 0.0;
  if (minus.valid && plus.valid) {
    s = distance_sq(minus, plus) * 0.25;
  } else if (plus.valid) {
    s = distance_sq(centre, plus);
  } else if (minus.valid) {
    s = distance_sq(minus, centre);
  }
  return s;
}

void main() {
  const int i = int(gl_GlobalInvocationID.x);
  const int j = int(gl_GlobalInvocationID.y);
  const uint local = gl_LocalInvocationIndex;
  if (local < RELIEF_GROUP_SIZE / 4) {
    valid_words[local] = 0u;
  }
  barrier();
  const bool in_row = i < domain.pitch;  // the last work group of a row may overhang it
  const int k = j * domain.pitch + i;
  bool valid = false;
  if (in_row) {
    precise float dx = 0.0, dz = 0.0, sigma = 0.0, nu = 1.0;
    if (i < domain.width) {
      const Row here = domain_row(j);
      const Footprint centre = footprint(i, j, here);
      if (centre.valid) {
        const Row below = domain_row(j - 1);
        const Row above = domain_row(j + 1);
        precise float along_row =
            axis_spacing_sq(footprint(i - 1, j, here), centre, footprint(i + 1, j, here));
        precise float along_column =
            axis_spacing_sq(footprint(i, j - 1, below), centre, footprint(i, j + 1, above));
        precise float spacing_sq = along_row < along_column ? along_column : along_row;
        nu = domain.nu_max;
        if (spacing_sq > domain.min_spacing_sq) {
          // std::clamp(c0 - c1 log2(sigma^2), 1, N), log2 as det_math.h's.
          precise float lod = domain.c0 - domain.c1 * log2_det(spacing_sq);
          nu = lod < 1.0 ? 1.0 : (domain.nu_max < lod ? domain.nu_max : lod);
        }
        if (domain.whole_octaves != 0) {
          nu = ceil(nu);
        }
        dx = centre.x;
        dz = centre.z;
        sigma = square_root(spacing_sq);
        valid = true;
      }
    }
    out_dx[k] = dx;
    out_dz[k] = dz;
    out_sigma[k] = sigma;
    out_nu[k] = nu;
  }
  if (valid) {
    atomicOr(valid_words[local >> 2], 1u << (8u * (local & 3u)));
  }
  barrier();
  if (in_row && (local & 3u) == 0u) {
    out_valid[k >> 2] = valid_words[local >> 2];
  }
}
