//! Bounds checks on accessors before the `gltf` crate's reader walks them.
//!
//! The reader computes `offset + stride·(count − 1) + size` and slices with it; a count of 0, a
//! stride smaller than an element or sizes near `usize::MAX` would make that arithmetic fail.
//! Every range is checked here first, with overflow-checked arithmetic, so that reading a file
//! never panics.

use ::gltf::Accessor;
use ::gltf::accessor::{DataType, Dimensions};
use ::gltf::buffer::View;

/// Why `accessor` cannot serve as an attribute of `dimensions` with a component type among
/// `types`, stored in `buffers`; `Ok` when every byte it names exists.
pub fn check_accessor(
    accessor: &Accessor,
    types: &[DataType],
    dimensions: Dimensions,
    buffers: &[Vec<u8>],
) -> Result<(), String> {
    if !types.contains(&accessor.data_type()) || accessor.dimensions() != dimensions {
        return Err(format!(
            "holds {:?} {:?}, expected {:?} of {:?}",
            accessor.dimensions(),
            accessor.data_type(),
            dimensions,
            types
        ));
    }
    if accessor.count() == 0 {
        return Err("its count is 0".into());
    }
    let size = accessor.size();
    if let Some(view) = accessor.view() {
        check_range(&view, accessor.offset(), accessor.count(), size, buffers)?;
    }
    if let Some(sparse) = accessor.sparse() {
        if sparse.count() == 0 {
            return Err("its sparse count is 0".into());
        }
        let indices = sparse.indices();
        let index_size = indices.index_type().size();
        check_range(
            &indices.view(),
            indices.offset(),
            sparse.count(),
            index_size,
            buffers,
        )
        .map_err(|e| format!("sparse indices: {e}"))?;
        let values = sparse.values();
        check_range(
            &values.view(),
            values.offset(),
            sparse.count(),
            size,
            buffers,
        )
        .map_err(|e| format!("sparse values: {e}"))?;
    }
    Ok(())
}

/// Checks that `count` elements of `size` bytes from `offset` in `view` lie inside the view,
/// and the view inside its buffer's loaded bytes.
fn check_range(
    view: &View,
    offset: usize,
    count: usize,
    size: usize,
    buffers: &[Vec<u8>],
) -> Result<(), String> {
    let stride = view.stride().unwrap_or(size);
    if stride < size {
        return Err(format!(
            "buffer view {} has a stride of {stride} bytes, less than an element's {size}",
            view.index()
        ));
    }
    let end = stride
        .checked_mul(count - 1)
        .and_then(|n| n.checked_add(size))
        .and_then(|n| n.checked_add(offset));
    if end.is_none_or(|end| end > view.length()) {
        return Err(format!(
            "{count} elements from byte {offset} run past the end of buffer view {} ({} bytes)",
            view.index(),
            view.length()
        ));
    }
    let buffer_len = buffers.get(view.buffer().index()).map_or(0, Vec::len);
    let view_end = view.offset().checked_add(view.length());
    if view_end.is_none_or(|end| end > buffer_len) {
        return Err(format!(
            "buffer view {} runs past the end of buffer {} ({buffer_len} bytes)",
            view.index(),
            view.buffer().index()
        ));
    }
    Ok(())
}
