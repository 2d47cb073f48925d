//! Separable Gaussian-derivative filters for the grey-edge family (§5), a port of
//! the kernels of van de Weijer's `gDer` / `norm_derivative.m`.
//!
//! Kernels are applied by *correlation* (`filter2`), x first then y, with
//! replicate padding. The first-order kernel is normalised so that a unit ramp
//! has derivative +1, and the second-order one so that x² has second derivative 2.
//! Every output pixel depends only on inputs within Chebyshev distance
//! [`kernel_radius`], which is what the mask dilation relies on.

/// Kernel radius R = floor(3σ + 0.5): taps −R..=R.
pub(crate) fn kernel_radius(sigma: f64) -> usize {
    (3.0 * sigma + 0.5).floor().max(0.0) as usize
}

/// 1-D Gaussian-derivative kernel of the given order (0, 1 or 2), taps −R..=R.
pub(crate) fn gaussian_kernel(sigma: f64, order: u8) -> Vec<f64> {
    let r = kernel_radius(sigma) as i64;
    let xs: Vec<f64> = (-r..=r).map(|x| x as f64).collect();
    let s2 = sigma * sigma;
    let g: Vec<f64> = xs
        .iter()
        .map(|x| libm::exp(-x * x / (2.0 * s2)) / ((2.0 * std::f64::consts::PI).sqrt() * sigma))
        .collect();
    match order {
        0 => {
            let sum: f64 = g.iter().sum();
            g.iter().map(|v| v / sum).collect()
        }
        1 => {
            let g1: Vec<f64> = xs.iter().zip(&g).map(|(x, g)| -(x / s2) * g).collect();
            let norm: f64 = xs.iter().zip(&g1).map(|(x, k)| x * k).sum();
            g1.iter().map(|k| k / norm).collect()
        }
        2 => {
            let g2: Vec<f64> = xs
                .iter()
                .zip(&g)
                .map(|(x, g)| (x * x / (s2 * s2) - 1.0 / s2) * g)
                .collect();
            let mean = g2.iter().sum::<f64>() / g2.len() as f64;
            let g2: Vec<f64> = g2.iter().map(|k| k - mean).collect();
            let norm: f64 = xs.iter().zip(&g2).map(|(x, k)| 0.5 * x * x * k).sum();
            g2.iter().map(|k| k / norm).collect()
        }
        _ => panic!("Gaussian derivative order {order} is not supported (0, 1 or 2)"),
    }
}

/// Correlates every row with `kernel`, replicating edge pixels.
/// `src` and the result are row-major `width × height`.
fn correlate_rows(src: &[f64], width: usize, kernel: &[f64]) -> Vec<f64> {
    let r = kernel.len() / 2;
    let mut dst = vec![0.0; src.len()];
    // One padded copy of the row, so the inner loop has no bounds clamping.
    let mut padded = vec![0.0; width + 2 * r];
    for (row, out) in src.chunks_exact(width).zip(dst.chunks_exact_mut(width)) {
        padded[..r].fill(row[0]);
        padded[r..r + width].copy_from_slice(row);
        padded[r + width..].fill(row[width - 1]);
        for (x, o) in out.iter_mut().enumerate() {
            *o = kernel.iter().zip(&padded[x..]).map(|(k, v)| k * v).sum();
        }
    }
    dst
}

/// Correlates every column with `kernel`, replicating edge pixels. Works a
/// whole row at a time (tap-outer, pixel-inner) to stay cache-friendly.
fn correlate_cols(src: &[f64], width: usize, height: usize, kernel: &[f64]) -> Vec<f64> {
    let r = kernel.len() / 2;
    let mut dst = vec![0.0; src.len()];
    for (y, out) in dst.chunks_exact_mut(width).enumerate() {
        for (t, k) in kernel.iter().enumerate() {
            let sy = (y + t).saturating_sub(r).min(height - 1);
            let row = &src[sy * width..(sy + 1) * width];
            for (o, v) in out.iter_mut().zip(row) {
                *o += k * v;
            }
        }
    }
    dst
}

/// `gDer(f, σ, x_order, y_order)`: the image filtered with the order-`x_order`
/// kernel along x, then the order-`y_order` kernel along y.
pub(crate) fn gaussian_derivative(
    img: &[f64],
    width: usize,
    height: usize,
    sigma: f64,
    x_order: u8,
    y_order: u8,
) -> Vec<f64> {
    let fx = correlate_rows(img, width, &gaussian_kernel(sigma, x_order));
    correlate_cols(&fx, width, height, &gaussian_kernel(sigma, y_order))
}

/// Per-pixel magnitude of the order-n derivative (`norm_derivative.m`):
/// n = 0 → smoothed |f|; n = 1 → √(f_x² + f_y²); n = 2 → √(f_xx² + 4f_xy² + f_yy²).
pub(crate) fn derivative_magnitude(
    img: &[f64],
    width: usize,
    height: usize,
    sigma: f64,
    n: u8,
) -> Vec<f64> {
    let d = |i, j| gaussian_derivative(img, width, height, sigma, i, j);
    match n {
        0 => d(0, 0).into_iter().map(f64::abs).collect(),
        1 => {
            let (fx, fy) = (d(1, 0), d(0, 1));
            fx.iter()
                .zip(&fy)
                .map(|(a, b)| libm::hypot(*a, *b))
                .collect()
        }
        2 => {
            let (fxx, fyy, fxy) = (d(2, 0), d(0, 2), d(1, 1));
            (0..img.len())
                .map(|i| (fxx[i] * fxx[i] + 4.0 * fxy[i] * fxy[i] + fyy[i] * fyy[i]).sqrt())
                .collect()
        }
        _ => panic!("derivative order {n} is not supported (0, 1 or 2)"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn kernel_normalisations() {
        for sigma in [0.5, 1.0, 2.0, 3.3] {
            let r = kernel_radius(sigma) as f64;
            let xs = || (0..).map(move |i| i as f64 - r);
            let k0 = gaussian_kernel(sigma, 0);
            assert!((k0.iter().sum::<f64>() - 1.0).abs() < 1e-12);
            let k1 = gaussian_kernel(sigma, 1);
            let m1: f64 = k1.iter().zip(xs()).map(|(k, x)| k * x).sum();
            assert!((m1 - 1.0).abs() < 1e-12 && k1.iter().sum::<f64>().abs() < 1e-12);
            let k2 = gaussian_kernel(sigma, 2);
            let m2: f64 = k2.iter().zip(xs()).map(|(k, x)| 0.5 * x * x * k).sum();
            assert!((m2 - 1.0).abs() < 1e-12 && k2.iter().sum::<f64>().abs() < 1e-12);
        }
        assert_eq!(gaussian_kernel(1.0, 0).len(), 7);
    }

    #[test]
    fn derivatives_of_ramps() {
        // f = 2x + 3y on 16×12: interior f_x = 2, f_y = 3, magnitude √13.
        let (w, h) = (16, 12);
        let img: Vec<f64> = (0..w * h)
            .map(|i| 2.0 * (i % w) as f64 + 3.0 * (i / w) as f64)
            .collect();
        let fx = gaussian_derivative(&img, w, h, 1.0, 1, 0);
        let fy = gaussian_derivative(&img, w, h, 1.0, 0, 1);
        let mag = derivative_magnitude(&img, w, h, 1.0, 1);
        let mid = 6 * w + 8;
        assert!((fx[mid] - 2.0).abs() < 1e-12 && (fy[mid] - 3.0).abs() < 1e-12);
        assert!((mag[mid] - 13f64.sqrt()).abs() < 1e-12);
        // Second order of x²: f_xx = 2, f_xy = f_yy = 0.
        let sq: Vec<f64> = (0..w * h).map(|i| ((i % w) as f64).powi(2)).collect();
        assert!((derivative_magnitude(&sq, w, h, 1.0, 2)[mid] - 2.0).abs() < 1e-9);
    }

    #[test]
    fn replicate_padding_keeps_constants_flat() {
        let img = vec![0.7; 5 * 4];
        for n in 0..=2 {
            let m = derivative_magnitude(&img, 5, 4, 2.0, n);
            let want = if n == 0 { 0.7 } else { 0.0 };
            assert!(m.iter().all(|v| (v - want).abs() < 1e-12), "n = {n}: {m:?}");
        }
    }
}
