//! [`Af`]: the envelope in affine arithmetic (Comba & Stolfi), a fourth [`Real`] beside
//! [`Iv`]. Intervals forget where a value came from: x − x is [−w, w], and a shading that
//! reads one slope twenty times widens twenty times. An affine form keeps a value as
//! c + Σ aᵢεᵢ ± e over noise symbols εᵢ ∈ [−1, 1] shared by every value computed from the
//! same input, so such dependencies cancel; e holds what no symbol tracks (the roundings the
//! rules allow, the linearisations' remainders).
//!
//! Every `Af` also carries the [`Iv`] that interval arithmetic gives for the same
//! operations, and its value is the intersection of the two: never wider than the interval
//! envelope, and sound because each is. An operation without an affine rule here (`pow`,
//! `atan2`, `round`, a `max` the bounds cannot decide, the union of two branches) gives its
//! interval as a fresh noise symbol: one value wherever it is used, correlated with itself
//! though not with its inputs. That relies on the mirror computing a value once where the WGSL
//! does (the random GPUs follow the mirror's dataflow and cannot check it), and on symbols
//! never crossing threads (the counter is per thread: one fragment is shaded on one thread).

use std::cell::Cell;
use std::ops::{Add, Div, Mul, Neg, Sub};

use super::interval::{DIV_ULPS, F32_MIN_NORMAL, divisor_defined};
use super::{ByteRange, Iv, Real, Tri, f32_ulp};

/// How many noise symbols a form keeps; past that the smallest fold into its error.
pub const TERMS: usize = 12;

/// The relative error f64 may add to a form's coefficients in one operation, covered
/// outright (f64 rounds each coefficient within 2⁻⁵³; a few of them per operation).
const F64_REL: f64 = 1e-15;

thread_local! {
    static NEXT_SYMBOL: Cell<u32> = const { Cell::new(1) };
}

/// A fresh noise symbol (never 0: 0 marks an unused slot).
fn fresh() -> u32 {
    NEXT_SYMBOL.with(|n| {
        let id = n.get();
        n.set(if id == u32::MAX { 1 } else { id + 1 });
        id
    })
}

/// c + Σ aᵢεᵢ ± e.
#[derive(Clone, Copy, Debug)]
struct Form {
    c: f64,
    ids: [u32; TERMS],
    co: [f64; TERMS],
    n: usize,
    e: f64,
    /// Σ|aᵢ| + e, summed once where the form is made ([`Form::seal`]): every operation reads
    /// its operands' radii, most of them twice.
    rad: f64,
}

impl Form {
    fn constant(c: f64, e: f64) -> Form {
        Form { c, ids: [0; TERMS], co: [0.0; TERMS], n: 0, e, rad: e }
    }

    /// The form with its radius summed from its terms (after they changed).
    fn seal(mut self) -> Form {
        self.rad = self.co[..self.n].iter().map(|a| a.abs()).sum::<f64>() + self.e;
        self
    }

    /// Σ|aᵢ| + e.
    fn radius(&self) -> f64 {
        self.rad
    }

    /// α·a + β·b + γ, plus `extra` error; symbols merged by id, the smallest folded into the
    /// error past [`TERMS`].
    fn combine(a: &Form, alpha: f64, b: &Form, beta: f64, gamma: f64, extra: f64) -> Form {
        let e = alpha.abs() * a.e + beta.abs() * b.e + extra;
        Form::combine_terms(a, alpha, b, beta, gamma, e)
    }

    /// α·a + β·b + γ of the two forms' centres and symbols (not their errors), with error `e`.
    fn combine_terms(a: &Form, alpha: f64, b: &Form, beta: f64, gamma: f64, e: f64) -> Form {
        let mut ids = [0u32; 2 * TERMS];
        let mut co = [0f64; 2 * TERMS];
        let mut n = 0;
        // A zero coefficient is written and not counted, so the merge has no branch on it.
        let mut push = |id: u32, v: f64| {
            ids[n] = id;
            co[n] = v;
            n += usize::from(v != 0.0);
        };
        let (mut i, mut j) = (0, 0);
        // The merge takes the smaller id, or both when equal, without a branch on which: the
        // ids interleave unpredictably, and a mispredicted branch per step cost more than
        // the step. A side not taken adds +0.0, which changes no coefficient that is kept (a
        // −0.0 becomes +0.0, and neither is counted).
        while i < a.n && j < b.n {
            let (x, y) = (a.ids[i], b.ids[j]);
            let (take_a, take_b) = (x <= y, y <= x);
            let va = if take_a { alpha * a.co[i] } else { 0.0 };
            let vb = if take_b { beta * b.co[j] } else { 0.0 };
            push(x.min(y), va + vb);
            i += usize::from(take_a);
            j += usize::from(take_b);
        }
        // One side is done; a literal's form has no symbol at all, the common case.
        for k in i..a.n {
            push(a.ids[k], alpha * a.co[k]);
        }
        for k in j..b.n {
            push(b.ids[k], beta * b.co[k]);
        }
        let c = alpha * a.c + beta * b.c + gamma;
        let mut e = e;
        let terms = co[..n].iter().map(|v| v.abs()).sum::<f64>();
        let mag = c.abs() + terms + e;
        e += mag * F64_REL;
        Form::fold(c, &ids[..n], &co[..n], e, terms)
    }

    /// Keeps the [`TERMS`] largest coefficients (in id order), the rest added to the error.
    /// `ids` holds at most 2·[`TERMS`] (a combination of two forms); `terms` is Σ|co| in
    /// their order, the radius's sum when all are kept (the same sum, so the same bits).
    fn fold(c: f64, ids: &[u32], co: &[f64], mut e: f64, terms: f64) -> Form {
        // The kept terms go to arrays of their own and the form is built once at the end:
        // filling a `Form` field by field and then moving it (`seal(self)`) made the copy
        // read wider than the stores just made, a store-forwarding stall on every operation.
        let mut out_ids = [0u32; TERMS];
        let mut out_co = [0f64; TERMS];
        let k = ids.len();
        if k <= TERMS {
            out_ids[..k].copy_from_slice(ids);
            out_co[..k].copy_from_slice(co);
            return Form { c, ids: out_ids, co: out_co, n: k, e, rad: terms + e };
        }
        // Keep a term when fewer than TERMS others rank before it: larger, or as large and
        // earlier (ties kept in id order). The ranks are counted over the whole stack-held
        // list without a branch (padding at −1 never ranks before a magnitude ≥ 0): a sort
        // of 24 was a fifth of every combination. A NaN magnitude ranks oddly, but a NaN
        // coefficient leaves the form unbounded either way (its radius is NaN).
        let mut mags = [-1.0f64; 2 * TERMS];
        for (m, a) in mags.iter_mut().zip(co) {
            *m = a.abs();
        }
        let mut n = 0;
        for i in 0..k {
            let m = mags[i];
            let mut rank = 0usize;
            for (j, &o) in mags.iter().enumerate() {
                rank += usize::from(o > m) + usize::from(o == m && j < i);
            }
            if rank < TERMS {
                out_ids[n] = ids[i];
                out_co[n] = co[i];
                n += 1;
            } else {
                e += m;
            }
        }
        let rad = out_co[..n].iter().map(|a| a.abs()).sum::<f64>() + e;
        Form { c, ids: out_ids, co: out_co, n, e, rad }
    }

    /// The product (linear part exact; the symbols' product within radius × radius).
    fn mul(a: &Form, b: &Form, extra: f64) -> Form {
        let rest = a.radius() * b.radius() + a.c.abs() * b.e + b.c.abs() * a.e;
        // c_a·b_lin + c_b·a_lin − c_a·c_b (the constant counted twice; the linear parts
        // without their errors, which `rest` holds).
        Form::combine_terms(b, a.c, a, b.c, -a.c * b.c, rest + extra)
    }
}

/// A value of the envelope in affine arithmetic: its interval ([`Iv`]'s own arithmetic) and,
/// where one is known, its affine form; the value lies in both.
#[derive(Clone, Copy, Debug)]
pub struct Af {
    iv: Iv,
    form: Option<Form>,
}

impl Af {
    /// A value known only to lie in `iv`, correlated with nothing before it: one fresh
    /// noise symbol (an input of the computation: a varying, a texel read).
    pub fn input(iv: Iv) -> Af {
        if iv.full || !iv.lo.is_finite() || !iv.hi.is_finite() {
            return Af { iv, form: None };
        }
        let c = 0.5 * (iv.lo + iv.hi);
        let r = 0.5 * (iv.hi - iv.lo);
        let mut f = Form::constant(c, (c.abs() + r) * F64_REL);
        if r > 0.0 {
            f.ids[0] = fresh();
            f.co[0] = r;
            f.n = 1;
            f = f.seal();
        }
        Af { iv, form: Some(f) }
    }

    /// The result of an operation carried by its interval alone: one value in `iv` wherever it
    /// is used, so a fresh noise symbol of its own ([`Af::input`]): what is computed from it
    /// twice stays correlated (the gamma of a sky's three Perez functions).
    fn interval(iv: Iv) -> Af {
        Af::input(iv)
    }

    /// The value with its interval replaced by `iv`, which another sound rule gives for the
    /// same value (a texture filter's envelope): the form kept.
    pub fn cut(self, iv: Iv) -> Af {
        Af::with(iv, self.form)
    }

    /// The interval of the value: the affine form's range cut by the interval's.
    pub fn to_iv(self) -> Iv {
        if self.iv.full {
            return self.iv;
        }
        match self.form {
            Some(f) => {
                // The radius sums up to 13 terms in f64: an outward margin for their roundings.
                let r = f.radius() * (1.0 + 1e-14);
                let (lo, hi) =
                    ((f.c - r).next_down().max(self.iv.lo), (f.c + r).next_up().min(self.iv.hi));
                if lo <= hi { Iv::new(lo, hi) } else { self.iv }
            }
            None => self.iv,
        }
    }

    /// The affine form, or one made of the interval (its centre, its half-width as error).
    fn form_or_iv(&self) -> Option<Form> {
        if let Some(f) = self.form {
            return Some(f);
        }
        let v = self.iv;
        (!v.full && v.lo.is_finite() && v.hi.is_finite()).then(|| {
            let c = 0.5 * (v.lo + v.hi);
            Form::constant(c, 0.5 * (v.hi - v.lo) + c.abs() * F64_REL)
        })
    }

    /// What one rounding of a result that `iv` bounds may add under `ulps` ULP (at twice its
    /// magnitude: a rounding up into the next binade), with a flushed subnormal's 2⁻¹²⁶.
    fn rounding(iv: Iv, ulps: f64) -> f64 {
        ulps * f32_ulp(2.0 * iv.magnitude()) + F32_MIN_NORMAL
    }

    /// `iv` with `form` when both are finite; else a fresh symbol over `iv` ([`Af::interval`]),
    /// or the interval alone where it is unbounded.
    fn with(iv: Iv, form: Option<Form>) -> Af {
        if iv.full {
            return Af { iv, form: None };
        }
        match form.filter(|f| f.c.is_finite() && f.radius().is_finite()) {
            Some(f) => Af { iv, form: Some(f) },
            None => Af::input(iv),
        }
    }

    /// An increasing function of the value `f` with the interval's result `iv`, by the
    /// min-range linearisation: slope `alpha` (its least derivative on the range), so
    /// f(x) − αx is increasing and its range over [lo, hi] is [g(lo), g(hi)]; the rule's
    /// allowance is what the interval result leaves around f's exact range.
    fn increasing(self, iv: Iv, f: fn(f64) -> f64, alpha: impl Fn(f64, f64) -> f64) -> Af {
        let x = self.to_iv();
        let Some(form) = self.form.filter(|_| !iv.full && !x.full) else {
            return Af::with(iv, None);
        };
        let (lo, hi) = (x.lo, x.hi);
        let a = alpha(lo, hi);
        let (g_lo, g_hi) = (f(lo) - a * lo, f(hi) - a * hi);
        let inner = x;
        // What the interval result leaves around f's exact range, and a flushed subnormal.
        let allowance = (f(inner.lo) - iv.lo).max(iv.hi - f(inner.hi)).max(0.0) + F32_MIN_NORMAL;
        let zeta = 0.5 * (g_lo + g_hi);
        // f64's own roundings of f and of the differences.
        let f64_err = (f(lo).abs() + (a * lo).abs() + f(hi).abs() + (a * hi).abs()) * F64_REL;
        let delta = 0.5 * (g_hi - g_lo).abs() + allowance + f64_err;
        let zero = Form::constant(0.0, 0.0);
        let out = Form::combine(&form, a, &zero, 0.0, zeta, delta);
        Af::with(iv, Some(out))
    }
}

impl Af {
    /// `self + beta·b` for β = ±1 (exact scalings), whose interval `iv` is: the forms
    /// combined with one rounding's allowance.
    fn plus(self, b: Af, beta: f64, iv: Iv) -> Af {
        let form = match (self.form_or_iv(), b.form_or_iv()) {
            (Some(x), Some(y)) if self.form.is_some() || b.form.is_some() => {
                Some(Form::combine(&x, 1.0, &y, beta, 0.0, Af::rounding(iv, 1.0)))
            }
            _ => None,
        };
        Af::with(iv, form)
    }
}

impl Add for Af {
    type Output = Af;
    fn add(self, b: Af) -> Af {
        let iv = self.to_iv() + b.to_iv();
        self.plus(b, 1.0, iv)
    }
}

/// `a + (−b)` in one step: the same bits (negation is exact, and so is a product by ±1),
/// without building the negated form.
impl Sub for Af {
    type Output = Af;
    fn sub(self, b: Af) -> Af {
        let iv = self.to_iv() - b.to_iv();
        self.plus(b, -1.0, iv)
    }
}

impl Neg for Af {
    type Output = Af;
    fn neg(self) -> Af {
        let form = self.form.map(|f| {
            let mut g = f;
            g.c = -f.c;
            for a in &mut g.co[..g.n] {
                *a = -*a;
            }
            g
        });
        Af { iv: -self.to_iv(), form }
    }
}

impl Mul for Af {
    type Output = Af;
    fn mul(self, b: Af) -> Af {
        let iv = self.to_iv() * b.to_iv();
        let form = match (self.form_or_iv(), b.form_or_iv()) {
            (Some(x), Some(y)) if self.form.is_some() || b.form.is_some() => {
                Some(Form::mul(&x, &y, Af::rounding(iv, 1.0)))
            }
            _ => None,
        };
        Af::with(iv, form)
    }
}

impl Div for Af {
    type Output = Af;
    /// a · (1/b), 1/b by the min-range linearisation of a convex function of constant sign
    /// (slope −1/m², m the divisor's larger magnitude), the quotient's rule (2.5 ULP) for
    /// the whole.
    fn div(self, b: Af) -> Af {
        let iv = self.to_iv() / b.to_iv();
        let d = b.to_iv();
        let (Some(bf), Some(af)) = (b.form_or_iv(), self.form_or_iv()) else {
            return Af::with(iv, None);
        };
        if iv.full || d.full || (d.lo <= 0.0 && d.hi >= 0.0) {
            return Af::with(iv, None);
        }
        let (m_lo, m_hi) = (d.lo.abs().min(d.hi.abs()), d.magnitude());
        if !divisor_defined(m_lo)
            || !divisor_defined(m_hi)
            || (self.form.is_none() && b.form.is_none())
        {
            return Af::with(iv, None);
        }
        // On [lo, hi] of one sign: g(y) = 1/y + y/m² is monotone; its range gives ζ ± δ.
        let (lo, hi) = (d.lo, d.hi);
        let alpha = -1.0 / (m_hi * m_hi);
        let (g_lo, g_hi) = (1.0 / lo - alpha * lo, 1.0 / hi - alpha * hi);
        let zeta = 0.5 * (g_lo + g_hi);
        let f64_err = (1.0 / lo.abs() + (alpha * lo).abs()) * 2.0 * F64_REL;
        let delta = 0.5 * (g_hi - g_lo).abs() + f64_err;
        let zero = Form::constant(0.0, 0.0);
        let recip = Form::combine(&bf, alpha, &zero, 0.0, zeta, delta);
        Af::with(iv, Some(Form::mul(&af, &recip, Af::rounding(iv, DIV_ULPS))))
    }
}

impl Real for Af {
    type Cond = Tri;
    fn lit(v: f32) -> Af {
        let iv = Iv::point(v);
        if iv.full {
            return Af::interval(iv);
        }
        let c = 0.5 * (iv.lo + iv.hi);
        Af { iv, form: Some(Form::constant(c, 0.5 * (iv.hi - iv.lo))) }
    }
    fn max(self, b: Af) -> Af {
        let iv = self.to_iv().max(b.to_iv());
        let (x, y) = (self.to_iv(), b.to_iv());
        if !x.full && !y.full {
            if x.lo >= y.hi {
                return Af { iv, form: self.form };
            }
            if y.lo >= x.hi {
                return Af { iv, form: b.form };
            }
        }
        Af::interval(Iv::max(x, y))
    }
    fn min(self, b: Af) -> Af {
        let iv = self.to_iv().min(b.to_iv());
        let (x, y) = (self.to_iv(), b.to_iv());
        if !x.full && !y.full {
            if x.hi <= y.lo {
                return Af { iv, form: self.form };
            }
            if y.hi <= x.lo {
                return Af { iv, form: b.form };
            }
        }
        Af::interval(Iv::min(x, y))
    }
    fn pow(self, e: Af) -> Af {
        Af::interval(self.to_iv().pow(e.to_iv()))
    }
    fn round(self) -> Af {
        Af::interval(self.to_iv().round())
    }
    fn abs(self) -> Af {
        let x = self.to_iv();
        if !x.full && x.lo >= 0.0 {
            return self;
        }
        if !x.full && x.hi <= 0.0 {
            return -self;
        }
        Af::interval(x.abs())
    }
    fn floor_cases(self) -> Option<[Option<(f32, Af)>; 2]> {
        let cases = self.to_iv().floor_cases()?;
        Some(cases.map(|c| {
            c.map(|(k, t)| {
                let t_af = self - Af::lit(k);
                (k, Af { iv: t_af.iv.within(t.lo, t.hi), form: t_af.form })
            })
        }))
    }
    fn frexp_cases(self) -> Option<[Option<(i32, Af)>; 2]> {
        let cases = self.to_iv().frexp_cases()?;
        Some(cases.map(|c| {
            c.map(|(e, m)| {
                // Scaling by a power of two is exact.
                let s = 2f64.powi(-e);
                let form = self.form.map(|f| {
                    let zero = Form::constant(0.0, 0.0);
                    Form::combine(&f, s, &zero, 0.0, 0.0, 0.0)
                });
                (e, Af { iv: m, form })
            })
        }))
    }
    fn exp(self) -> Af {
        let iv = self.to_iv().exp();
        self.increasing(iv, f64::exp, |lo, _| lo.exp())
    }
    fn atan2(self, x: Af) -> Af {
        Af::interval(self.to_iv().atan2(x.to_iv()))
    }
    /// sqrt over a positive normal range by the min-range linearisation (slope 1/(2√hi));
    /// the interval alone where the range reaches 0 (the slope there is unbounded).
    fn sqrt(self) -> Af {
        let iv = self.to_iv().sqrt();
        let x = self.to_iv();
        if x.full || x.lo < F32_MIN_NORMAL {
            return Af::with(iv, None);
        }
        self.increasing(iv, f64::sqrt, |_, hi| 0.5 / hi.sqrt())
    }
    fn le(self, b: Af) -> Tri {
        self.to_iv().le(b.to_iv())
    }
    fn lt(self, b: Af) -> Tri {
        self.to_iv().lt(b.to_iv())
    }
    fn eq(self, b: Af) -> Tri {
        self.to_iv().eq(b.to_iv())
    }
    fn sq(self) -> Af {
        let iv = self.to_iv().sq();
        let form = self.form.map(|f| Form::mul(&f, &f, Af::rounding(iv, 1.0)));
        Af::with(iv, form)
    }
    const INTERVAL: bool = true;
    fn least(self) -> f64 {
        self.to_iv().least()
    }
    fn within(self, lo: f64, hi: f64) -> Af {
        Af { iv: self.iv.within(lo, hi), form: self.form }
    }
    fn hull(self, b: Af) -> Af {
        Af::interval(self.to_iv().hull(b.to_iv()))
    }
    fn select(f: Af, t: Af, cond: Tri) -> Af {
        match cond {
            Tri::True => t,
            Tri::False => f,
            Tri::Either => f.hull(t),
        }
    }
    fn store_unorm8(self) -> ByteRange {
        self.to_iv().store_unorm8()
    }
    fn store_half(self) -> Af {
        Af::interval(self.to_iv().store_half())
    }
    /// The exact sum's form, with the interval sum's allowance for any order of evaluation
    /// (what [`Iv::sum`] adds to the exact bounds).
    fn sum(terms: &[Af]) -> Af {
        let ivs: Vec<Iv> = terms.iter().map(|t| t.to_iv()).collect();
        let iv = Iv::sum(&ivs);
        if iv.full || terms.iter().all(|t| t.form.is_none()) {
            return Af::with(iv, None);
        }
        let exact_lo: f64 = ivs.iter().map(|t| t.lo).sum();
        let exact_hi: f64 = ivs.iter().map(|t| t.hi).sum();
        let allowance = (exact_lo - iv.lo).max(iv.hi - exact_hi).max(0.0) * (1.0 + 1e-12);
        let zero = Form::constant(0.0, 0.0);
        let mut acc = Form::constant(0.0, 0.0);
        for t in terms {
            let Some(f) = t.form_or_iv() else { return Af::with(iv, None) };
            acc = Form::combine(&acc, 1.0, &f, 1.0, 0.0, 0.0);
        }
        Af::with(iv, Some(Form::combine(&acc, 1.0, &zero, 0.0, 0.0, allowance)))
    }
    fn sum_as_written(terms: &[Af], _: impl FnOnce(&[Af]) -> Af) -> Af {
        Self::sum(terms)
    }
}

#[cfg(test)]
mod tests {
    use super::super::{Jitter, JitterRules};
    use super::*;

    /// A shading-like expression in which x and y recur: the dependency intervals lose.
    fn expr<R: Real>(x: R, y: R) -> R {
        let l = R::lit;
        let n = (x * x + y).sqrt();
        let s = n / (l(1.0) + (-x).exp());
        s - x * y + (x - y).sq() + (x * l(0.75) - y) / (x + l(2.0))
    }

    const X: (f32, f32) = (0.55, 0.65);
    const Y: (f32, f32) = (0.10, 0.14);

    fn at(k: u32, n: u32, (lo, hi): (f32, f32)) -> f32 {
        lo + (hi - lo) * (k as f32 / n as f32)
    }

    fn enclosure() -> (Iv, Iv) {
        let (x, y) = (Iv::new(X.0.into(), X.1.into()), Iv::new(Y.0.into(), Y.1.into()));
        (expr(Af::input(x), Af::input(y)).to_iv(), expr(x, y))
    }

    #[test]
    fn x_minus_x_is_its_roundings_only() {
        let x = Af::input(Iv::new(1.0, 2.0));
        let d = (x - x).to_iv();
        assert!(d.hi - d.lo < 1e-6, "{d:?}");
        let i = Iv::new(1.0, 2.0);
        let di = i - i;
        assert!(di.hi - di.lo >= 2.0, "{di:?}");
    }

    #[test]
    fn exact_and_random_conformant_results_stay_inside_and_the_form_is_narrower() {
        let (af, iv) = enclosure();
        let (mut outside, mut shrunk_outside) = (0, 0);
        let mid = 0.5 * (af.lo + af.hi);
        let shrunk = Iv::new(mid - 0.3 * (af.hi - af.lo), mid + 0.3 * (af.hi - af.lo));
        let n = 40;
        let (mut least, mut most) = (f64::INFINITY, f64::NEG_INFINITY);
        for i in 0..=n {
            for j in 0..=n {
                let (x, y) = (at(i, n, X), at(j, n, Y));
                let exact = expr(x, y);
                (least, most) = (least.min(exact.into()), most.max(exact.into()));
                outside += usize::from(!af.contains(exact));
                shrunk_outside += usize::from(!shrunk.contains(exact));
                for seed in 0..4 {
                    Jitter::reseed(JitterRules { seed, scale: 1.0 }, u64::from(i * 1000 + j));
                    let r = expr(Jitter(x), Jitter(y)).0;
                    outside += usize::from(!af.contains(r));
                }
            }
        }
        assert_eq!(outside, 0, "affine enclosure {af:?}");
        // The negative control: an enclosure 60 % as wide misses values.
        assert!(shrunk_outside > 0, "{shrunk:?} holds every value: the test cannot fail");
        // And the point of it: within 10 % of the values' own range, where the intervals are
        // over 20 % wider.
        let range = most - least;
        assert!(af.hi - af.lo < 1.1 * range, "affine {af:?}, values [{least}, {most}]");
        assert!(iv.hi - iv.lo > 1.2 * range, "interval {iv:?}, values [{least}, {most}]");
    }

    #[test]
    fn a_form_past_its_terms_folds_into_its_error_and_stays_sound() {
        let l = Af::lit;
        let xs: Vec<(f32, Af)> = (0..2 * TERMS)
            .map(|k| {
                let v = 1.0 + k as f32 / 8.0;
                (v, Af::input(Iv::new(f64::from(v) - 0.01, f64::from(v) + 0.01)))
            })
            .collect();
        let sum = xs.iter().fold(l(0.0), |a, (_, x)| a + *x * l(0.5));
        let exact = xs.iter().fold(0.0f32, |a, (v, _)| a + v * 0.5);
        let r = sum.to_iv();
        assert!(r.contains(exact), "{r:?} misses {exact}");
        // 24 inputs of radius 0.01 times 0.5: radius 0.12 plus roundings.
        assert!(r.hi - r.lo < 0.25, "{r:?}");
    }
}
