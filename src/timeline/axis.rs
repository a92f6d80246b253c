//! The time axis: steps of 1, 2 or 5 × 10ⁿ, labelled in the unit the step suits.

/// A step of 1, 2 or 5 × 10ⁿ ns giving at most about `count` steps over `span_ns`.
pub fn step(span_ns: u64, count: u64) -> u64 {
    let raw = (span_ns / count.max(1)).max(1);
    let mut magnitude = 1u64;
    while magnitude.saturating_mul(10) <= raw {
        magnitude *= 10;
    }
    [1, 2, 5, 10]
        .into_iter()
        .map(|factor| magnitude.saturating_mul(factor))
        .find(|step| *step >= raw)
        .unwrap_or(u64::MAX)
}

/// A tick's time in the unit of the window's end (`to_ns`), with as many decimals as the step
/// needs: `250 µs`, `9.5 ms`, `20 s`.
pub fn label(t_ns: u64, step_ns: u64, to_ns: u64) -> String {
    let (unit, per) = match to_ns {
        1_000_000_000.. => ("s", 1_000_000_000u64),
        1_000_000.. => ("ms", 1_000_000),
        1_000.. => ("µs", 1_000),
        _ => ("ns", 1),
    };
    let mut decimals = 0;
    let mut resolution = per;
    while resolution > 1 && !step_ns.is_multiple_of(resolution) {
        resolution /= 10;
        decimals += 1;
    }
    format!("{:.*} {unit}", decimals, t_ns as f64 / per as f64)
}

/// The ticks from `from` to `to`: multiples of the step.
pub fn ticks(from: u64, to: u64, step_ns: u64) -> impl Iterator<Item = u64> {
    let first = from.div_ceil(step_ns) * step_ns;
    (0..)
        .map(move |n| first.saturating_add(n * step_ns))
        .take_while(move |t| *t <= to)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn steps_are_one_two_five_and_labels_whole() {
        assert_eq!(step(507_000, 8), 100_000);
        assert_eq!(step(60_000_000_000, 8), 10_000_000_000);
        assert_eq!(step(1_000, 8), 200);
        assert_eq!(label(300_000, 100_000, 507_000), "300 µs");
        assert_eq!(
            label(20_000_000_000, 10_000_000_000, 60_000_000_000),
            "20 s"
        );
        assert_eq!(label(9_500_000, 500_000, 12_500_000), "9.5 ms");
        assert_eq!(label(1_250_000, 250_000, 2_000_000), "1.25 ms");
        let ticks: Vec<u64> = ticks(150, 520, 100).collect();
        assert_eq!(ticks, [200, 300, 400, 500]);
    }
}
