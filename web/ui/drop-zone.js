// Files dropped on `target` (the whole page in the app, the viewer when embedded):
// `root` shows the drop hint while a file is dragged over, `onFile` gets the first file.
export function attachDropZone(target, root, onFile) {
  const onDragOver = (e) => {
    if (![...(e.dataTransfer?.types ?? [])].includes('Files')) return;
    e.preventDefault();
    root.classList.add('vqsa-dragging');
  };
  const onDragLeave = (e) => {
    if (e.target === target || !target.contains(e.relatedTarget)) root.classList.remove('vqsa-dragging');
  };
  const onDrop = (e) => {
    root.classList.remove('vqsa-dragging');
    const file = e.dataTransfer?.files?.[0];
    if (!file) return;
    e.preventDefault();
    onFile(file);
  };
  target.addEventListener('dragover', onDragOver);
  target.addEventListener('dragleave', onDragLeave);
  target.addEventListener('drop', onDrop);
  return () => {
    target.removeEventListener('dragover', onDragOver);
    target.removeEventListener('dragleave', onDragLeave);
    target.removeEventListener('drop', onDrop);
  };
}
