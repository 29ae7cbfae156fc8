//! Viewport tiling: 1 viewport fills the window, 2 and 3 sit side by side (equal sizes, so
//! that decimations compare at one scale, and no empty quadrant), 4 share a 2×2 grid
//! (reading order). Pure arithmetic, shared by the shot action and the viewer.

/// A pixel rectangle inside the window or image.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Rect {
    pub x: u32,
    pub y: u32,
    pub width: u32,
    pub height: u32,
}

impl Rect {
    /// True when the pixel `(px, py)` lies inside.
    pub fn contains(&self, px: f64, py: f64) -> bool {
        px >= f64::from(self.x)
            && py >= f64::from(self.y)
            && px < f64::from(self.x + self.width)
            && py < f64::from(self.y + self.height)
    }

    /// Width / height, 1 for an empty rectangle.
    pub fn aspect(&self) -> f32 {
        if self.width == 0 || self.height == 0 {
            1.0
        } else {
            self.width as f32 / self.height as f32
        }
    }
}

/// Gap in pixels between neighbouring tiles (shows the separator colour).
pub const GAP: u32 = 2;

/// The rectangles of `count` viewports (clamped to 1..=4) in a `width` × `height` area.
pub fn tiles(count: usize, width: u32, height: u32) -> Vec<Rect> {
    let (cols, rows) = match count.clamp(1, 4) {
        1 => (1, 1),
        2 => (2, 1),
        3 => (3, 1),
        _ => (2, 2),
    };
    let cell = |i: u32, n: u32, size: u32| {
        // Split `size` into `n` cells with a gap between them; the last cell takes the rest.
        let gaps = GAP * (n - 1);
        let each = size.saturating_sub(gaps) / n;
        let start = i * (each + GAP);
        let len = if i + 1 == n {
            size.saturating_sub(start)
        } else {
            each
        };
        (start.min(size), len)
    };
    (0..count.clamp(1, 4) as u32)
        .map(|i| {
            let (x, width) = cell(i % cols, cols, width);
            let (y, height) = cell(i / cols, rows, height);
            Rect {
                x,
                y,
                width,
                height,
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_fills_two_split_four_grid() {
        assert_eq!(
            tiles(1, 320, 240),
            vec![Rect {
                x: 0,
                y: 0,
                width: 320,
                height: 240
            }]
        );
        let two = tiles(2, 320, 240);
        assert_eq!(
            two[0],
            Rect {
                x: 0,
                y: 0,
                width: 159,
                height: 240
            }
        );
        assert_eq!(
            two[1],
            Rect {
                x: 161,
                y: 0,
                width: 159,
                height: 240
            }
        );
        let four = tiles(4, 320, 240);
        assert_eq!(
            four[3],
            Rect {
                x: 161,
                y: 121,
                width: 159,
                height: 119
            }
        );
    }

    #[test]
    fn every_count_covers_the_whole_area_but_the_gaps() {
        for count in 1..=4 {
            let rects = tiles(count, 320, 240);
            assert_eq!(rects.len(), count);
            let area: u32 = rects.iter().map(|r| r.width * r.height).sum();
            // Gaps of GAP pixels between columns and rows only: no empty cell.
            let (cols, rows) = [(1, 1), (2, 1), (3, 1), (2, 2)][count - 1];
            let expected = (320 - GAP * (cols - 1)) * (240 - GAP * (rows - 1));
            assert!(
                area.abs_diff(expected) <= 2 * 240,
                "{count} viewports cover {area} of {expected} pixels"
            );
        }
        let three = tiles(3, 320, 240);
        assert_eq!((three[2].x + three[2].width, three[2].height), (320, 240));
    }

    #[test]
    fn contains_is_half_open() {
        let r = tiles(2, 320, 240)[1];
        assert!(r.contains(161.0, 0.0));
        assert!(!r.contains(160.0, 10.0));
        assert!(!r.contains(320.0, 10.0));
    }
}
