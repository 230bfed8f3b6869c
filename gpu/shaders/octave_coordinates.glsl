// The exact coordinate form of core/octave_coordinates.h: g_n d mod P from the float pieces of
// g_n, each product split exactly by Dekker's two-product (Veltkamp's split) and each sum's
// rounding error carried aside by Knuth's two-sum. These error-free transformations are only
// error-free when every + - * is rounded once, in the order written: a compiler that contracts
// a * b - p into an FMA, or simplifies t - (t - a) to a, computes something else. Hence every
// variable here is precise (GLSL 4.50 §4.7: no contraction, no reassociation, no
// simplification of the operations that produce it).

// Veltkamp's split a = hi + lo, each half at most 12 significant bits (splitter 2^12 + 1).
vec2 split_halves(float a) {
  precise float t = 4097.0 * a;
  precise float hi = t - (t - a);
  precise float lo = a - hi;
  return vec2(hi, lo);
}

// a * b - product exactly, from the halves of a and b (Dekker 1971).
float product_error(float a_hi, float a_lo, float b_hi, float b_lo, float product) {
  precise float e = ((a_hi * b_hi - product) + a_hi * b_lo + a_lo * b_hi) + a_lo * b_lo;
  return e;
}

// a + b - sum exactly, sum = a + b rounded (two-sum).
float sum_error(float a, float b, float sum) {
  precise float b_virtual = sum - a;
  precise float a_virtual = sum - b_virtual;
  precise float e = (a - a_virtual) + (b - b_virtual);
  return e;
}

// One term of exact_scaled_mod: wrapped, added to the running sum with its rounding error
// carried aside, the sum wrapped again. state = (sum, carry).
vec2 add_wrapped_term(vec2 state, float term, float period, float inv_period) {
  precise float sum = state.x;
  precise float carry = state.y;
  precise float wrapped = wrap_period(term, period, inv_period);
  precise float total = sum + wrapped;
  carry = carry + sum_error(sum, wrapped, total);
  sum = wrap_period(total, period, inv_period);
  return vec2(sum, carry);
}

// g_n d mod P in [0, P]: `piece`, `piece_hi`, `piece_lo` the pieces of g_n, largest first,
// and their halves, d_halves the halves of d; the smallest piece first, its product's error
// before the product, the carry added once at the end.
float exact_scaled_mod(float piece[3], float piece_hi[3], float piece_lo[3], float d,
                       vec2 d_halves, float period, float inv_period) {
  precise vec2 state = vec2(0.0);
  for (int q = 2; q >= 0; --q) {
    precise float product = d * piece[q];
    precise float error =
        product_error(d_halves.x, d_halves.y, piece_hi[q], piece_lo[q], product);
    state = add_wrapped_term(state, error, period, inv_period);
    state = add_wrapped_term(state, product, period, inv_period);
  }
  precise float result = wrap_period(state.x + state.y, period, inv_period);
  return result;
}
